#include "core/calibration/umbmark.hpp"

#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "core/sim/diff_drive.hpp"

namespace irgs {

namespace {

void requireSetup(const UmbmarkSetup& setup) {
  if (!std::isfinite(setup.side_m) || setup.side_m <= 0.0 || !std::isfinite(setup.wheelbase_m) ||
      setup.wheelbase_m <= 0.0)
    throw std::invalid_argument("UMBmark: side and wheelbase must be finite and > 0");
}

// The four centre-of-gravity coordinates the exact model predicts: (x_cw, y_cw, x_ccw, y_ccw).
Eigen::Vector4d predictAll(const UmbmarkSetup& setup, double e_d, double e_b) {
  const Vec2 cw = predictUmbmarkError(UmbmarkDirection::kClockwise, setup, e_d, e_b);
  const Vec2 ccw = predictUmbmarkError(UmbmarkDirection::kCounterClockwise, setup, e_d, e_b);
  return {cw.x(), cw.y(), ccw.x(), ccw.y()};
}

}  // namespace

const char* toString(UmbmarkDirection direction) {
  return direction == UmbmarkDirection::kClockwise ? "cw" : "ccw";
}

Vec2 predictUmbmarkError(UmbmarkDirection direction, const UmbmarkSetup& setup,
                         double wheel_diameter_ratio, double wheelbase_ratio) {
  requireSetup(setup);
  if (!std::isfinite(wheel_diameter_ratio) || wheel_diameter_ratio <= 0.0 ||
      !std::isfinite(wheelbase_ratio) || wheelbase_ratio <= 0.0)
    throw std::invalid_argument("predictUmbmarkError: ratios must be finite and > 0");
  // True travel per believed travel of each wheel, mean 1 (paper eq. 17 inverted).
  const double c_left = 2.0 / (wheel_diameter_ratio + 1.0);
  const double c_right = 2.0 * wheel_diameter_ratio / (wheel_diameter_ratio + 1.0);
  const double b = setup.wheelbase_m, b_true = wheelbase_ratio * b;
  const double s = direction == UmbmarkDirection::kCounterClockwise ? 1.0 : -1.0;
  const double turn_wheel_m = s * 0.5 * kPi * 0.5 * b;  // right wheel travel of a believed turn
  Pose2 truth;
  for (int leg = 0; leg < 4; ++leg) {
    if (leg > 0) {
      // On-the-spot turn of s * 90 deg as the odometry sees it: wheels d_R = -d_L.
      const double ds = 0.5 * (c_right - c_left) * turn_wheel_m;
      const double dtheta = (c_right + c_left) * turn_wheel_m / b_true;
      truth = integrateArc(truth, ds, dtheta);
    }
    // Straight leg as the odometry sees it (d_R = d_L = L): an arc in truth.
    truth = integrateArc(truth, 0.5 * (c_right + c_left) * setup.side_m,
                         (c_right - c_left) * setup.side_m / b_true);
  }
  return truth.position();  // the odometry ends at the origin
}

UmbmarkAnalysis analyseUmbmark(std::span<const UmbmarkRun> runs, const UmbmarkSetup& setup) {
  requireSetup(setup);
  UmbmarkAnalysis a;
  const double L = setup.side_m, b = setup.wheelbase_m;
  Vec2 sum_cw = Vec2::Zero(), sum_ccw = Vec2::Zero();
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const UmbmarkRun& r = runs[i];
    if (!r.error_m.allFinite()) {
      a.diagnostics.push_back("run " + std::to_string(i + 1) + ": non-finite error, skipped");
      continue;
    }
    if (r.direction == UmbmarkDirection::kClockwise) {
      sum_cw += r.error_m;
      ++a.cw_runs;
    } else {
      sum_ccw += r.error_m;
      ++a.ccw_runs;
    }
  }
  if (a.cw_runs == 0 || a.ccw_runs == 0) {
    a.diagnostics.push_back("needs at least one clockwise and one counter-clockwise run (" +
                            std::to_string(a.cw_runs) + " cw, " + std::to_string(a.ccw_runs) +
                            " ccw usable)");
    return a;
  }
  // (U1) centres of gravity.
  a.cg_cw = sum_cw / static_cast<double>(a.cw_runs);
  a.cg_ccw = sum_ccw / static_cast<double>(a.ccw_runs);
  double ss_cw = 0.0, ss_ccw = 0.0;
  for (const UmbmarkRun& r : runs) {
    if (!r.error_m.allFinite())
      continue;
    if (r.direction == UmbmarkDirection::kClockwise)
      ss_cw += (r.error_m - a.cg_cw).squaredNorm();
    else
      ss_ccw += (r.error_m - a.cg_ccw).squaredNorm();
  }
  a.spread_cw_m = std::sqrt(ss_cw / static_cast<double>(a.cw_runs));
  a.spread_ccw_m = std::sqrt(ss_ccw / static_cast<double>(a.ccw_runs));
  // (U2) E_max,syst.
  a.e_max_syst_m = std::max(a.cg_cw.norm(), a.cg_ccw.norm());
  if (a.e_max_syst_m > 0.5 * L) {
    a.diagnostics.push_back(
        "return errors exceed half the square's side: the robot did not drive "
        "the square, or the errors were entered in other units");
    return a;
  }

  // (U3), (U4) the paper's closed form, from the x coordinates.
  a.alpha_rad = (a.cg_cw.x() + a.cg_ccw.x()) / (-4.0 * L);
  a.beta_rad = (a.cg_cw.x() - a.cg_ccw.x()) / (-4.0 * L);
  // (U5) R = (L/2) / sin(beta/2); (U6) E_d = (R + b/2) / (R - b/2) written with
  // q = (b/2) / R = b sin(beta/2) / L so beta = 0 needs no infinity.
  const double half_sin = std::sin(0.5 * a.beta_rad);
  a.radius_m = half_sin == 0.0 ? std::numeric_limits<double>::infinity() : 0.5 * L / half_sin;
  const double q = b * half_sin / L;
  // (U7) E_b = 90 deg / (90 deg - alpha).
  if (std::abs(q) >= 1.0 || a.alpha_rad >= 0.5 * kPi) {
    a.diagnostics.push_back("return errors too large for the UMBmark model");
    return a;
  }
  a.wheel_diameter_ratio_linear = (1.0 + q) / (1.0 - q);
  a.wheelbase_ratio_linear = 0.5 * kPi / (0.5 * kPi - a.alpha_rad);

  // (U8) Gauss-Newton on the exact model, all four coordinates, from the closed form.
  const Eigen::Vector4d measured(a.cg_cw.x(), a.cg_cw.y(), a.cg_ccw.x(), a.cg_ccw.y());
  Eigen::Vector2d p(a.wheel_diameter_ratio_linear, a.wheelbase_ratio_linear);
  bool converged = false;
  for (int iteration = 0; iteration < 50 && !converged; ++iteration) {
    const Eigen::Vector4d r = predictAll(setup, p.x(), p.y()) - measured;
    Eigen::Matrix<double, 4, 2> J;
    constexpr double kH = 1e-6;
    for (int k = 0; k < 2; ++k) {
      Eigen::Vector2d hi = p, lo = p;
      hi[k] += kH;
      lo[k] -= kH;
      J.col(k) = (predictAll(setup, hi.x(), hi.y()) - predictAll(setup, lo.x(), lo.y())) / (2 * kH);
    }
    const Eigen::Vector2d step = (J.transpose() * J).ldlt().solve(-J.transpose() * r);
    if (!step.allFinite())
      break;
    p += step;
    if (!(p.x() > 0.1 && p.x() < 10.0 && p.y() > 0.1 && p.y() < 10.0))
      break;
    converged = step.norm() < 1e-12;
  }
  if (!converged || !p.allFinite()) {
    a.diagnostics.push_back("the exact model did not converge; using the paper's closed form");
    p = {a.wheel_diameter_ratio_linear, a.wheelbase_ratio_linear};
  }
  a.wheel_diameter_ratio = p.x();
  a.wheelbase_ratio = p.y();
  a.fit_residual_m = std::sqrt((predictAll(setup, p.x(), p.y()) - measured).squaredNorm() / 4.0);
  a.ok = true;
  return a;
}

OdometryCorrection correctOdometry(const OdometryCorrection& current, double wheel_diameter_ratio,
                                   double wheelbase_ratio) {
  if (!(std::isfinite(current.left_wheel_scale) && current.left_wheel_scale > 0.0 &&
        std::isfinite(current.right_wheel_scale) && current.right_wheel_scale > 0.0 &&
        std::isfinite(current.wheelbase_m) && current.wheelbase_m > 0.0 &&
        std::isfinite(wheel_diameter_ratio) && wheel_diameter_ratio > 0.0 &&
        std::isfinite(wheelbase_ratio) && wheelbase_ratio > 0.0))
    throw std::invalid_argument("correctOdometry: scales, wheelbase and ratios must be > 0");
  // Paper eq. 17.
  const double c_left = 2.0 / (wheel_diameter_ratio + 1.0);
  const double c_right = 2.0 / (1.0 / wheel_diameter_ratio + 1.0);
  double left = current.left_wheel_scale * c_left, right = current.right_wheel_scale * c_right;
  const double mean = 0.5 * (left + right);
  left /= mean;
  right /= mean;
  return {left, right, current.wheelbase_m * wheelbase_ratio};
}

}  // namespace irgs
