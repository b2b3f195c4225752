#include "core/estimation/ekf_localizer.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <stdexcept>

#include "core/estimation/stereo_measurement_model.hpp"

namespace irgs {

namespace {

void checkStateAndCovariance(const LocState& x0, const LocCov& p0) {
  if (!x0.allFinite() || !p0.allFinite())
    throw std::invalid_argument("EkfLocalizer: non-finite initial state or covariance");
  if (!(p0 - p0.transpose()).isZero(1e-9 * (1.0 + p0.cwiseAbs().maxCoeff())))
    throw std::invalid_argument("EkfLocalizer: initial covariance is not symmetric");
  const Eigen::SelfAdjointEigenSolver<LocCov> eig(p0);
  if (eig.eigenvalues().minCoeff() < -1e-12)
    throw std::invalid_argument("EkfLocalizer: initial covariance is not positive semi-definite");
}

// Rotation body -> world by Phi, embedded in 3x3 with the heading row untouched.
LocCov bodyToWorld(double phi) {
  const double c = std::cos(phi), s = std::sin(phi);
  LocCov r;
  r << c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0;
  return r;
}

}  // namespace

void validate(const EkfLocalizerConfig& config) {
  if (!(config.eps1_m >= 0.0) || !std::isfinite(config.eps1_m))
    throw std::invalid_argument("EkfLocalizerConfig: eps1_m must be >= 0 and finite");
  if (!(config.eps2_rad >= 0.0) || !std::isfinite(config.eps2_rad))
    throw std::invalid_argument("EkfLocalizerConfig: eps2_rad must be >= 0 and finite");
  if (!(config.gate > 0.0))  // +infinity allowed (the paper's value)
    throw std::invalid_argument("EkfLocalizerConfig: gate must be > 0 (may be infinity)");
  if (!(config.r_d_m2 > 0.0) || !std::isfinite(config.r_d_m2) || !(config.r_theta_rad2 > 0.0) ||
      !std::isfinite(config.r_theta_rad2))
    throw std::invalid_argument("EkfLocalizerConfig: R_d and R_theta must be > 0 and finite");
}

const char* toString(UpdateStatus status) {
  switch (status) {
    case UpdateStatus::kUpdated:
      return "updated";
    case UpdateStatus::kRejectedNonFinite:
      return "rejected: non-finite input";
    case UpdateStatus::kInvalidEcho:
      return "rejected: (5)/(6) validity check";
    case UpdateStatus::kNoMatch:
      return "no match";
    case UpdateStatus::kGated:
      return "rejected by the gate";
  }
  return "unknown";
}

const char* toString(MatchKind kind) {
  switch (kind) {
    case MatchKind::kNone:
      return "none";
    case MatchKind::kWall:
      return "wall";
    case MatchKind::kCorner:
      return "corner";
    case MatchKind::kEdge:
      return "edge";
  }
  return "unknown";
}

EkfLocalizer::EkfLocalizer(const LocState& x0, const LocCov& p0, EkfLocalizerConfig config)
    : config_(config) {
  validate(config_);
  reset(x0, p0);
}

void EkfLocalizer::reset(const LocState& x0, const LocCov& p0) {
  checkStateAndCovariance(x0, p0);
  x_ = x0;
  x_(kLocPhi) = wrapAngle(x_(kLocPhi));
  p_ = 0.5 * (p0 + p0.transpose());
}

void EkfLocalizer::propagate(const LocState& x_new, const LocCov& f, const LocCov& q) {
  x_ = x_new;
  x_(kLocPhi) = wrapAngle(x_(kLocPhi));
  // P_{k|k-1} = F P F' + Q
  const LocCov p = f * p_ * f.transpose() + q;
  p_ = 0.5 * (p + p.transpose());
}

PredictStatus EkfLocalizer::predictDiffDrive(double left_m, double right_m, double wheelbase_m,
                                             const DiffDriveNoise& noise) {
  if (!std::isfinite(left_m) || !std::isfinite(right_m) || !std::isfinite(wheelbase_m) ||
      !(wheelbase_m > 0.0) || !std::isfinite(noise.wheel_variance_per_m) ||
      !(noise.wheel_variance_per_m >= 0.0) || !noise.per_step.allFinite())
    return PredictStatus::kRejectedNonFinite;
  const double ds = 0.5 * (left_m + right_m);
  const double dphi = (right_m - left_m) / wheelbase_m;
  const double a = x_(kLocPhi) + 0.5 * dphi;  // midpoint heading
  const double ca = std::cos(a), sa = std::sin(a);

  LocState x_new = x_;
  x_new(kLocX) += ds * ca;
  x_new(kLocY) += ds * sa;
  x_new(kLocPhi) += dphi;

  // F = d f / d U
  LocCov f = LocCov::Identity();
  f(kLocX, kLocPhi) = -ds * sa;
  f(kLocY, kLocPhi) = ds * ca;
  // G = d f / d (left, right)
  Eigen::Matrix<double, 3, 2> g;
  const double k = ds / (2.0 * wheelbase_m);
  g << 0.5 * ca + k * sa, 0.5 * ca - k * sa,  //
      0.5 * sa - k * ca, 0.5 * sa + k * ca,   //
      -1.0 / wheelbase_m, 1.0 / wheelbase_m;
  const Eigen::Vector2d wheel_var(noise.wheel_variance_per_m * std::abs(left_m),
                                  noise.wheel_variance_per_m * std::abs(right_m));
  const LocCov q = g * wheel_var.asDiagonal() * g.transpose() + noise.per_step;
  propagate(x_new, f, q);
  return PredictStatus::kApplied;
}

PredictStatus EkfLocalizer::predictBodyIncrement(const BodyTwist& body_delta,
                                                 const LocCov& body_cov) {
  if (!body_delta.allFinite() || !body_cov.allFinite())
    return PredictStatus::kRejectedNonFinite;
  const double a = x_(kLocPhi) + 0.5 * body_delta(2);  // midpoint heading
  const LocCov r = bodyToWorld(a);
  LocState x_new = x_ + r * body_delta;
  LocCov f = LocCov::Identity();
  f(kLocX, kLocPhi) = -std::sin(a) * body_delta(0) - std::cos(a) * body_delta(1);
  f(kLocY, kLocPhi) = std::cos(a) * body_delta(0) - std::sin(a) * body_delta(1);
  propagate(x_new, f, r * body_cov * r.transpose());
  return PredictStatus::kApplied;
}

CasterPrediction EkfLocalizer::predictCaster(const CasterDriveGeometry& geometry,
                                             const std::array<double, 3>& steering_rad,
                                             const CasterVector& delta_theta, double lambda) {
  CasterPrediction out;
  if (!delta_theta.allFinite() || !std::isfinite(lambda) || !(lambda >= 0.0))
    return out;
  for (double a : steering_rad) {
    if (!std::isfinite(a))
      return out;
  }
  return predictCaster(casterOdometry(geometry, steering_rad, delta_theta), lambda);
}

CasterPrediction EkfLocalizer::predictCaster(const CasterOdometry& odo, double lambda) {
  CasterPrediction out;
  if (!std::isfinite(lambda) || !(lambda >= 0.0))
    return out;
  if (!odo.ok) {
    out.status = PredictStatus::kRejectedCasterSingular;
    return out;
  }
  out.residual_norm = odo.residual_norm;
  // (36) Q_k = lambda ||e||_2 I6;  (37, A000-4) P += J+ Q J+' with J+ = R(Phi) G+ (A000-2), so
  // in the body frame the increment covariance is lambda ||e|| G+ G+'.
  const LocCov body_cov =
      lambda * odo.residual_norm * (odo.pseudo_inverse * odo.pseudo_inverse.transpose());
  // (34) U^_{k|k-1} = U^_{k-1|k-1} + J+ DeltaTheta
  out.status = predictBodyIncrement(odo.body_delta, body_cov);
  return out;
}

ScalarUpdate EkfLocalizer::scalarUpdate(double measured, double predicted, const LocRow& h,
                                        double r, bool is_angle) {
  ScalarUpdate u;
  u.attempted = true;
  u.measured = measured;
  u.predicted = predicted;
  // (48) V = Z - Z^  (angle innovations wrapped to (-pi, pi])
  u.innovation = is_angle ? wrapAngle(measured - predicted) : measured - predicted;
  // (44)/(45) S = grad P grad' + R
  const Eigen::Matrix<double, 3, 1> ph = p_ * h.transpose();
  u.s = h.dot(ph) + r;
  if (!(u.s > 0.0) || !std::isfinite(u.s) || !std::isfinite(u.innovation))
    return u;
  u.nis = u.innovation * u.innovation / u.s;
  // (49) V' S^-1 V <= g
  if (!(u.nis <= config_.gate))
    return u;
  // (50) W = P grad' S^-1
  const Eigen::Matrix<double, 3, 1> w = ph / u.s;
  // (51) U^_{k|k} = U^_{k|k-1} + W V
  x_ += w * u.innovation;
  x_(kLocPhi) = wrapAngle(x_(kLocPhi));
  // (52) in Joseph form: P = (I - W grad) P (I - W grad)' + W R W'
  const LocCov i_kh = LocCov::Identity() - w * h;
  const LocCov p = i_kh * p_ * i_kh.transpose() + (w * r) * w.transpose();
  p_ = 0.5 * (p + p.transpose());
  u.applied = true;
  return u;
}

LocalizationUpdate EkfLocalizer::update(const EchoPaths& reading, const StereoSensor& sensor,
                                        const LocalizationMap& map) {
  LocalizationUpdate result;
  if (!std::isfinite(reading.r1_m) || !std::isfinite(reading.r2_m) ||
      !std::isfinite(sensor.mount.x_m) || !std::isfinite(sensor.mount.y_m) ||
      !std::isfinite(sensor.mount.phi_rad) || !std::isfinite(sensor.half_baseline_m))
    return result;  // kRejectedNonFinite
  // (5)-(8) with the validity checks (first-stage error handling)
  const StereoInversion inv = invertSpecular(reading.r1_m, reading.r2_m, sensor.half_baseline_m);
  result.inversion = inv.status;
  if (!inv.ok()) {
    result.status = UpdateStatus::kInvalidEcho;
    return result;
  }
  result.measured_d_m = inv.d_m;
  result.measured_theta_rad = inv.theta_rad;
  return matchAndUpdate(result, &reading, sensor, map);
}

LocalizationUpdate EkfLocalizer::updateWithDistanceBearing(double d_m, double theta_rad,
                                                           const SensorMount& mount,
                                                           const LocalizationMap& map) {
  LocalizationUpdate result;
  if (!std::isfinite(d_m) || !std::isfinite(theta_rad) || !std::isfinite(mount.x_m) ||
      !std::isfinite(mount.y_m) || !std::isfinite(mount.phi_rad))
    return result;
  if (!(d_m > 0.0)) {
    result.status = UpdateStatus::kInvalidEcho;
    result.inversion = InversionStatus::kNegativeRadicand;
    return result;
  }
  result.inversion = InversionStatus::kOk;
  result.measured_d_m = d_m;
  result.measured_theta_rad = wrapAngle(theta_rad);
  return matchAndUpdate(result, nullptr, {mount, 0.0}, map);
}

LocalizationUpdate EkfLocalizer::matchAndUpdate(LocalizationUpdate result, const EchoPaths* reading,
                                                const StereoSensor& sensor,
                                                const LocalizationMap& map) {
  const SensorMount& mount = sensor.mount;
  const double d = result.measured_d_m;
  const double theta = result.measured_theta_rad;
  const Pose2 t = sensorWorldPose(x_, mount);  // (13)-(15)
  // (38) phi^_target = Phi^ + phi'_T + theta
  const double phi_target = wrapAngle(t.theta + theta);
  // (39)/(40) predicted reflector point: foot of the perpendicular or corner/edge point
  const Vec2 target = t.position() + d * Vec2(std::cos(phi_target), std::sin(phi_target));

  // Step 2, (41): nearest corner/edge within eps1
  double best_m1 = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < map.points.size(); ++i) {
    const double m1 = (map.points[i].position - target).norm();
    if (m1 <= config_.eps1_m && m1 < best_m1) {
      best_m1 = m1;
      result.feature_index = i;
    }
  }
  if (std::isfinite(best_m1)) {
    const MapPoint& point = map.points[result.feature_index];
    result.match = point.kind == PointFeatureKind::kEdge ? MatchKind::kEdge : MatchKind::kCorner;
    result.feature_id = point.id;
    result.match_metric = best_m1;
    if (result.match == MatchKind::kEdge && config_.use_edge_inverse && reading != nullptr) {
      const StereoInversion edge = invertEdge(reading->r1_m, reading->r2_m, sensor.half_baseline_m);
      if (edge.ok())
        result.measured_d_m = edge.d_m;
    }
    // Corners/edges: distance only, (18)/(19) with (46) per A000-3.
    const ScalarPrediction pred = predictPointDistance(x_, mount, point.position);
    result.distance =
        scalarUpdate(result.measured_d_m, pred.value, pred.jacobian, config_.r_d_m2, false);
    result.status = result.distance.applied ? UpdateStatus::kUpdated : UpdateStatus::kGated;
    return result;
  }

  // Step 3, (42)/(43): walls within eps2 of phi^_target, smallest m2 = |d^ - d| with d^ (17).
  double best_m2 = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < map.walls.size(); ++i) {
    const FacingLine& f = map.walls[i].facing;
    if (!(std::abs(wrapAngle(phi_target - f.phi_eff_rad)) <= config_.eps2_rad))
      continue;
    const double d_hat = predictWallDistance(x_, mount, f).value;
    if (!(d_hat > 0.0))
      continue;  // the sensor is behind this face: it cannot be the reflector
    const double m2 = std::abs(d_hat - d);
    if (m2 < best_m2) {
      best_m2 = m2;
      result.feature_index = i;
    }
  }
  if (!std::isfinite(best_m2)) {
    result.status = UpdateStatus::kNoMatch;
    return result;
  }
  const MapWallFace& wall = map.walls[result.feature_index];
  result.match = MatchKind::kWall;
  result.feature_id = wall.id;
  result.match_metric = best_m2;
  // Sequential scalar updates, d first, then theta re-linearised at the updated state.
  const ScalarPrediction pd = predictWallDistance(x_, mount, wall.facing);
  result.distance = scalarUpdate(d, pd.value, pd.jacobian, config_.r_d_m2, false);
  if (config_.use_bearing) {
    const ScalarPrediction pt = predictWallBearing(x_, mount, wall.facing);
    result.bearing = scalarUpdate(theta, pt.value, pt.jacobian, config_.r_theta_rad2, true);
  }
  result.status = (result.distance.applied || result.bearing.applied) ? UpdateStatus::kUpdated
                                                                      : UpdateStatus::kGated;
  return result;
}

}  // namespace irgs
