#include "core/estimation/encoder_gyro_filter.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace irgs {

namespace {

void require(bool condition, const std::string& what) {
  if (!condition)
    throw std::invalid_argument("EncoderGyroFilterConfig: " + what);
}

bool nonNegative(double v) {
  return std::isfinite(v) && v >= 0.0;
}

// Encoder dead reckoning, one step, heading at the middle of the step (second order; the error
// model (3) is evaluated at the same heading).
void integrate(Pose2& pose, double right_m, double left_m, double wheelbase_m) {
  const double ds = 0.5 * (right_m + left_m);
  const double dtheta = (right_m - left_m) / wheelbase_m;
  const double mid = pose.theta + 0.5 * dtheta;
  pose.x += std::cos(mid) * ds;
  pose.y += std::sin(mid) * ds;
  pose.theta = wrapAngle(pose.theta + dtheta);
}

}  // namespace

void validate(const EncoderGyroFilterConfig& c) {
  require(std::isfinite(c.wheelbase_m) && c.wheelbase_m > 0.0, "wheelbase_m must be > 0");
  require(nonNegative(c.initial_position_stddev_m) && nonNegative(c.initial_heading_stddev_rad) &&
              nonNegative(c.encoder_scale_stddev) && nonNegative(c.wheelbase_stddev_m) &&
              nonNegative(c.gyro_scale_stddev) && nonNegative(c.gyro_bias_stddev_radps),
          "initial stddevs must be finite and >= 0");
  require(nonNegative(c.wheel_travel_variance_per_m) &&
              nonNegative(c.gyro_angle_random_walk_rad2_per_s) &&
              nonNegative(c.gyro_bias_variance_rate_rad2_per_s3),
          "process noise must be finite and >= 0");
  require(std::isfinite(c.measurement_variance_rad2) && c.measurement_variance_rad2 > 0.0,
          "measurement_variance_rad2 must be > 0");
  require(!std::isnan(c.gate_nis) && c.gate_nis > 0.0, "gate_nis must be > 0 (may be +inf)");
  require(c.max_consecutive_gated >= 1, "max_consecutive_gated must be >= 1");
  require(c.max_heading_stddev_rad > 0.0 && !std::isnan(c.max_heading_stddev_rad),
          "max_heading_stddev_rad must be > 0");
  require(c.max_scale_correction > 0.0 && c.max_scale_correction < 1.0,
          "max_scale_correction must be in (0, 1)");
  require(c.max_gyro_bias_radps > 0.0 && !std::isnan(c.max_gyro_bias_radps),
          "max_gyro_bias_radps must be > 0");
  require(std::isfinite(c.initial_gyro_bias_radps), "initial_gyro_bias_radps must be finite");
  require(c.max_step_travel_m > 0.0 && !std::isnan(c.max_step_travel_m) &&
              c.max_gyro_rate_radps > 0.0 && !std::isnan(c.max_gyro_rate_radps),
          "max_step_travel_m and max_gyro_rate_radps must be > 0");
}

EncoderGyroFilter::EncoderGyroFilter(const EncoderGyroFilterConfig& config, const Pose2& start)
    : config_(config) {
  validate(config_);
  if (!std::isfinite(start.x) || !std::isfinite(start.y) || !std::isfinite(start.theta))
    throw std::invalid_argument("EncoderGyroFilter: non-finite start pose");
  pose_ = unfiltered_ = Pose2{start.x, start.y, wrapAngle(start.theta)};
  model_.gyro_bias_radps = config_.initial_gyro_bias_radps;
  restart();
}

DrCov EncoderGyroFilter::initialCovariance() const {
  const EncoderGyroFilterConfig& c = config_;
  DrState sigma;
  sigma << c.initial_position_stddev_m, c.initial_position_stddev_m, c.initial_heading_stddev_rad,
      c.encoder_scale_stddev, c.encoder_scale_stddev, c.wheelbase_stddev_m,
      c.initial_heading_stddev_rad, c.gyro_scale_stddev, c.gyro_bias_stddev_radps;
  return sigma.cwiseProduct(sigma).asDiagonal();
}

void EncoderGyroFilter::restart() {
  const double bias = model_.gyro_bias_radps;
  model_ = DrSensorModel{};
  model_.wheelbase_m = config_.wheelbase_m;
  model_.gyro_bias_radps = bias;
  gyro_heading_rad_ = pose_.theta;
  p_ = initialCovariance();
  mode_ = DrFilterMode::kFiltering;
  reason_ = DrFallbackReason::kNone;
  consecutive_gated_ = 0;
}

void EncoderGyroFilter::fallBack(DrFallbackReason reason) {
  mode_ = DrFilterMode::kFallback;
  reason_ = reason;
}

bool EncoderGyroFilter::healthy() const {
  const double limit = config_.max_scale_correction;
  return std::abs(model_.right_scale - 1.0) <= limit &&
         std::abs(model_.left_scale - 1.0) <= limit && std::abs(model_.gyro_scale - 1.0) <= limit &&
         std::abs(model_.wheelbase_m - config_.wheelbase_m) <= limit * config_.wheelbase_m &&
         std::abs(model_.gyro_bias_radps) <= config_.max_gyro_bias_radps;
}

DrStepResult EncoderGyroFilter::step(const DrStepInput& in) {
  DrStepResult result;
  if (!std::isfinite(in.right_m) || !std::isfinite(in.left_m) || !std::isfinite(in.dt_s) ||
      in.dt_s <= 0.0 || (in.gyro_rate_radps && !std::isfinite(*in.gyro_rate_radps)) ||
      std::abs(in.right_m) > config_.max_step_travel_m ||
      std::abs(in.left_m) > config_.max_step_travel_m ||
      (in.gyro_rate_radps && std::abs(*in.gyro_rate_radps) > config_.max_gyro_rate_radps))
    return result;  // kRejectedNonFinite

  integrate(unfiltered_, in.right_m, in.left_m, config_.wheelbase_m);
  if (mode_ == DrFilterMode::kFallback) {
    integrate(pose_, in.right_m, in.left_m, config_.wheelbase_m);
    result.status = DrStepStatus::kFallback;
    return result;
  }

  // Navigation through the corrected sensor model (001 2.6 steps 3-4).
  const double r = in.right_m * model_.right_scale;
  const double l = in.left_m * model_.left_scale;
  const double d = model_.wheelbase_m;
  const bool gyro = in.gyro_rate_radps.has_value();
  const double rate = gyro ? *in.gyro_rate_radps : 0.0;
  DrStepGeometry g;
  g.right_m = r;
  g.left_m = l;
  g.psi_rad = pose_.theta + 0.5 * (r - l) / d;
  g.wheelbase_m = d;
  g.omega_rad = rate * in.dt_s;
  g.dt_s = in.dt_s;
  g.gyro_valid = gyro;
  integrate(pose_, r, l, d);
  gyro_heading_rad_ = wrapAngle(
      gyro_heading_rad_ +
      (gyro ? (model_.gyro_scale * rate - model_.gyro_bias_radps) * in.dt_s : (r - l) / d));

  // (9) P <- F P F' + Q   (001 2.6 step 5)
  const DrCov f = drTransition(g);
  DrCov q = DrCov::Zero();
  {
    // Wheel travel noise, each wheel's variance proportional to its travel.
    Eigen::Matrix<double, kDrStates, 2> gw = Eigen::Matrix<double, kDrStates, 2>::Zero();
    const double c = std::cos(g.psi_rad), s = std::sin(g.psi_rad);
    gw.row(kDrDx) << 0.5 * c, 0.5 * c;
    gw.row(kDrDy) << 0.5 * s, 0.5 * s;
    gw.row(kDrDpsi) << 1.0 / d, -1.0 / d;
    if (!gyro)
      gw.row(kDrDphi) << 1.0 / d, -1.0 / d;
    const Eigen::Vector2d var(config_.wheel_travel_variance_per_m * std::abs(r),
                              config_.wheel_travel_variance_per_m * std::abs(l));
    q.noalias() = gw * var.asDiagonal() * gw.transpose();
    if (gyro)
      q(kDrDphi, kDrDphi) += config_.gyro_angle_random_walk_rad2_per_s * in.dt_s;
    q(kDrDbrb, kDrDbrb) += config_.gyro_bias_variance_rate_rad2_per_s3 * in.dt_s;
  }
  p_ = f * p_ * f.transpose() + q;
  p_ = 0.5 * (p_ + p_.transpose()).eval();

  if (!p_.allFinite() || std::sqrt(std::max(p_(kDrDpsi, kDrDpsi), p_(kDrDphi, kDrDphi))) >
                             config_.max_heading_stddev_rad) {
    fallBack(DrFallbackReason::kCovarianceBlowUp);
    result.status = DrStepStatus::kFallback;
    return result;
  }
  if (!gyro) {
    result.status = DrStepStatus::kPredictedOnly;
    return result;
  }

  // (10) Z = psi_enc - phi_gyro = H x + v, H = [0 0 -1 0 0 0 1 0 0]   (A001-4)
  const DrRow h = drMeasurementRow();
  const double z = wrapAngle(pose_.theta - gyro_heading_rad_);
  const double s = (h * p_ * h.transpose())(0, 0) + config_.measurement_variance_rad2;
  result.innovation_rad = z;
  result.innovation_variance = s;
  result.nis = z * z / s;
  if (!(result.nis <= config_.gate_nis)) {
    ++gated_;
    if (++consecutive_gated_ >= config_.max_consecutive_gated) {
      fallBack(DrFallbackReason::kInnovationTest);
      result.status = DrStepStatus::kFallback;
      return result;
    }
    result.status = DrStepStatus::kGated;
    return result;
  }
  consecutive_gated_ = 0;

  // K = P H' / S;  x = K Z;  P = (I - K H) P (I - K H)' + K R K'   (Joseph form)
  const DrState k = p_ * h.transpose() / s;
  const DrState x = k * z;
  const DrCov ikh = DrCov::Identity() - k * h;
  p_ = ikh * p_ * ikh.transpose() + k * config_.measurement_variance_rad2 * k.transpose();
  p_ = 0.5 * (p_ + p_.transpose()).eval();

  // Feedback into the navigation solution and the sensor models, then reset x to zero
  // (001 2.6 step 7). delta = true - computed, so every correction adds the estimate.
  pose_.x += x(kDrDx);
  pose_.y += x(kDrDy);
  pose_.theta = wrapAngle(pose_.theta + x(kDrDpsi));
  gyro_heading_rad_ = wrapAngle(gyro_heading_rad_ + x(kDrDphi));
  model_.right_scale *= 1.0 + x(kDrSr);
  model_.left_scale *= 1.0 + x(kDrSl);
  model_.wheelbase_m += x(kDrDd);
  model_.gyro_scale += x(kDrDbs);
  model_.gyro_bias_radps -= x(kDrDbrb);
  ++updates_;
  result.status = DrStepStatus::kUpdated;
  if (!healthy()) {
    fallBack(DrFallbackReason::kImplausibleCorrection);
    result.status = DrStepStatus::kFallback;
  }
  return result;
}

}  // namespace irgs
