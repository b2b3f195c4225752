#include "core/estimation/stereo_sonar.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace irgs {

namespace {

bool positiveFinite(double v) {
  return std::isfinite(v) && v > 0.0;
}

}  // namespace

void validate(const StereoSonarParams& params) {
  if (!positiveFinite(params.half_baseline_m))
    throw std::invalid_argument("StereoSonarParams: half_baseline_m must be > 0 and finite");
  if (!positiveFinite(params.speed_of_sound_mps))
    throw std::invalid_argument("StereoSonarParams: speed_of_sound_mps must be > 0 and finite");
  if (!positiveFinite(params.max_tof_s))
    throw std::invalid_argument("StereoSonarParams: max_tof_s must be > 0 and finite");
}

Vec2 receiver1Position(const Pose2& sensor, double half_baseline_m) {
  return sensor.toWorld({0.0, -half_baseline_m});
}

Vec2 receiver2Position(const Pose2& sensor, double half_baseline_m) {
  return sensor.toWorld({0.0, half_baseline_m});
}

EchoPaths wallEchoPaths(const WallLine& wall, const Pose2& sensor, double half_baseline_m) {
  // Mirror image of T: T' = T + 2 d n, n the unit direction from the sensor towards the wall.
  const FacingLine f = robotFacing(wall);
  const double d = predictedWallDistance(wall, sensor);
  const Vec2 n(std::cos(f.phi_eff_rad), std::sin(f.phi_eff_rad));
  const Vec2 image = sensor.position() + 2.0 * d * n;
  return {(image - receiver1Position(sensor, half_baseline_m)).norm(),
          (image - receiver2Position(sensor, half_baseline_m)).norm()};
}

EchoPaths wallEchoPathsLocal(double d_m, double theta_rad, double half_baseline_m) {
  const double s = half_baseline_m;
  const double common = s * s + 4.0 * d_m * d_m;
  const double cross_term = 4.0 * s * d_m * std::sin(theta_rad);
  // (3) r1^2 = s^2 + 4 d^2 + 4 s d sin(theta);  (4) r2^2 = s^2 + 4 d^2 - 4 s d sin(theta)
  return {std::sqrt(std::max(0.0, common + cross_term)),
          std::sqrt(std::max(0.0, common - cross_term))};
}

EchoPaths cornerEchoPaths(const Vec2& corner, const Pose2& sensor, double half_baseline_m) {
  const Vec2 image = 2.0 * corner - sensor.position();
  return {(image - receiver1Position(sensor, half_baseline_m)).norm(),
          (image - receiver2Position(sensor, half_baseline_m)).norm()};
}

EchoPaths edgeEchoPaths(const Vec2& edge, const Pose2& sensor, double half_baseline_m) {
  const double outward = (edge - sensor.position()).norm();
  return {outward + (edge - receiver1Position(sensor, half_baseline_m)).norm(),
          outward + (edge - receiver2Position(sensor, half_baseline_m)).norm()};
}

StereoInversion invertSpecular(double r1_m, double r2_m, double half_baseline_m) {
  StereoInversion out;
  if (!positiveFinite(r1_m) || !positiveFinite(r2_m) || !positiveFinite(half_baseline_m))
    return out;  // kNonFinite
  const double s = half_baseline_m;
  // (5) d = 0.5 sqrt((r1^2 + r2^2)/2 - s^2), radicand must be positive
  const double radicand = 0.5 * (r1_m * r1_m + r2_m * r2_m) - s * s;
  if (!(radicand > 0.0)) {
    out.status = InversionStatus::kNegativeRadicand;
    return out;
  }
  const double d = 0.5 * std::sqrt(radicand);
  // (6) theta = asin((r1^2 - r2^2) / (8 s d)), |argument| < 1; (7)/(8) sign follows r1 - r2
  const double arg = (r1_m - r2_m) * (r1_m + r2_m) / (8.0 * s * d);
  if (!(std::abs(arg) < 1.0)) {
    out.status = InversionStatus::kBearingOutOfRange;
    return out;
  }
  out.status = InversionStatus::kOk;
  out.d_m = d;
  out.theta_rad = std::asin(arg);
  return out;
}

StereoInversion invertEdge(double r1_m, double r2_m, double half_baseline_m) {
  StereoInversion out;
  if (!positiveFinite(r1_m) || !positiveFinite(r2_m) || !positiveFinite(half_baseline_m))
    return out;
  const double s = half_baseline_m;
  const double sum = r1_m + r2_m;
  // d = (r1^2 + r2^2 - 2 s^2) / (2 (r1 + r2)) [D]; the numerator plays the radicand's role.
  const double numerator = r1_m * r1_m + r2_m * r2_m - 2.0 * s * s;
  if (!(numerator > 0.0)) {
    out.status = InversionStatus::kNegativeRadicand;
    return out;
  }
  const double d = numerator / (2.0 * sum);
  // sin(theta) = (r1 - r2)(r1 + r2 - 2 d) / (4 d s) [D]
  const double arg = (r1_m - r2_m) * (sum - 2.0 * d) / (4.0 * d * s);
  if (!(std::abs(arg) < 1.0)) {
    out.status = InversionStatus::kBearingOutOfRange;
    return out;
  }
  out.status = InversionStatus::kOk;
  out.d_m = d;
  out.theta_rad = std::asin(arg);
  return out;
}

const char* toString(InversionStatus status) {
  switch (status) {
    case InversionStatus::kOk:
      return "ok";
    case InversionStatus::kNonFinite:
      return "non-finite or non-positive path length";
    case InversionStatus::kNegativeRadicand:
      return "negative radicand in (5)";
    case InversionStatus::kBearingOutOfRange:
      return "|asin argument| >= 1 in (6)";
  }
  return "unknown";
}

double tofToPathLength(double tof_s, double speed_of_sound_mps) {
  return tof_s * speed_of_sound_mps;
}

double pathLengthToTof(double path_m, double speed_of_sound_mps) {
  return path_m / speed_of_sound_mps;
}

bool withinMaxTof(const EchoPaths& paths, const StereoSonarParams& params) {
  const double t1 = pathLengthToTof(paths.r1_m, params.speed_of_sound_mps);
  const double t2 = pathLengthToTof(paths.r2_m, params.speed_of_sound_mps);
  return positiveFinite(t1) && positiveFinite(t2) && t1 <= params.max_tof_s &&
         t2 <= params.max_tof_s;
}

}  // namespace irgs
