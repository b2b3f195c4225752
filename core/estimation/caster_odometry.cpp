#include "core/estimation/caster_odometry.hpp"

#include <Eigen/Cholesky>
#include <cmath>
#include <stdexcept>

namespace irgs {

void validate(const CasterDriveGeometry& geometry) {
  if (!std::isfinite(geometry.wheel_radius_m) || !(geometry.wheel_radius_m > 0.0))
    throw std::invalid_argument("CasterDriveGeometry: wheel_radius_m must be > 0");
  if (!std::isfinite(geometry.offset_m) || !(geometry.offset_m > 0.0))
    throw std::invalid_argument("CasterDriveGeometry: offset_m (eps) must be > 0");
  for (const CasterModule& c : geometry.casters) {
    if (!std::isfinite(c.d_m) || !std::isfinite(c.alpha_rad))
      throw std::invalid_argument("CasterDriveGeometry: non-finite caster position");
  }
}

CasterG casterJacobian(const CasterDriveGeometry& geometry,
                       const std::array<double, 3>& steering_rad) {
  validate(geometry);
  const double r = geometry.wheel_radius_m;
  const double eps = geometry.offset_m;
  CasterG g;
  for (int i = 0; i < 3; ++i) {
    const auto k = static_cast<std::size_t>(i);
    const double phi = steering_rad[k];
    const double d = geometry.casters[k].d_m;
    const double alpha = geometry.casters[k].alpha_rad;
    // (26) G_i = [ cos(phi)/r     sin(phi)/r     d sin(phi - alpha)/r           ;
    //             -sin(phi)/eps   cos(phi)/eps   d cos(phi - alpha)/eps - 1     ]
    g.row(2 * i) << std::cos(phi) / r, std::sin(phi) / r, d * std::sin(phi - alpha) / r;
    g.row(2 * i + 1) << -std::sin(phi) / eps, std::cos(phi) / eps,
        d * std::cos(phi - alpha) / eps - 1.0;
  }
  return g;
}

CasterOdometry casterOdometry(const CasterDriveGeometry& geometry,
                              const std::array<double, 3>& steering_rad,
                              const CasterVector& delta_theta) {
  CasterOdometry out;
  if (!delta_theta.allFinite())
    return out;
  for (double a : steering_rad) {
    if (!std::isfinite(a))
      return out;
  }
  const CasterG g = casterJacobian(geometry, steering_rad);
  const Eigen::Matrix3d gtg = g.transpose() * g;
  const Eigen::LDLT<Eigen::Matrix3d> ldlt(gtg);
  // Rank check on the normal matrix: reject near-singular steering configurations.
  if (ldlt.info() != Eigen::Success || !(ldlt.vectorD().minCoeff() > 1e-12 * gtg.trace()))
    return out;
  // (33) J+ = (J'J)^-1 J'  ->  body frame G+ = (G'G)^-1 G'
  out.pseudo_inverse = ldlt.solve(g.transpose());
  out.body_delta = out.pseudo_inverse * delta_theta;
  // (35) e = (I - J J+) DeltaTheta = (I - G G+) DeltaTheta
  out.residual = delta_theta - g * out.body_delta;
  out.residual_norm = out.residual.norm();
  out.ok = out.body_delta.allFinite();
  return out;
}

std::array<double, 3> casterSteering(const CasterEncoders& encoders, double ticks_per_rad) {
  std::array<double, 3> out{};
  for (std::size_t i = 0; i < 3; ++i)
    out[i] = static_cast<double>(encoders.steering_ticks[i]) / ticks_per_rad;
  return out;
}

CasterOdometry casterIntervalOdometry(const CasterDriveGeometry& geometry,
                                      const CasterEncoders& from, const CasterEncoders& to,
                                      double ticks_per_rad, int k, int periods) {
  if (!(ticks_per_rad > 0.0) || !std::isfinite(ticks_per_rad) || periods < 1 || k < 0 ||
      k >= periods)
    return {};
  const double n = static_cast<double>(periods);
  const double mid = (static_cast<double>(k) + 0.5) / n;  // fraction of the interval
  std::array<double, 3> steering{};
  CasterVector delta;
  for (std::size_t i = 0; i < 3; ++i) {
    const double s0 = static_cast<double>(from.steering_ticks[i]);
    const double s1 = static_cast<double>(to.steering_ticks[i]);
    steering[i] = (s0 + mid * (s1 - s0)) / ticks_per_rad;
    const auto row = static_cast<Eigen::Index>(2 * i);
    delta(row) = static_cast<double>(to.drive_ticks[i] - from.drive_ticks[i]) / (n * ticks_per_rad);
    delta(row + 1) = (s1 - s0) / (n * ticks_per_rad);
  }
  return casterOdometry(geometry, steering, delta);
}

}  // namespace irgs
