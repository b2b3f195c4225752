#include "core/motion/drive_primitive.hpp"

#include <algorithm>
#include <cmath>

#include "core/motion/turn_control.hpp"

namespace irgs::motion {

bool DrivePrimitive::start(const DriveSpec& spec, const MotionInput& now,
                           const MotionSettings& settings, const MotionGeometry& geometry) {
  if (!std::isfinite(spec.distance_m) || spec.distance_m == 0.0 || !std::isfinite(spec.speed_mps) ||
      spec.speed_mps < 0.0 || !std::isfinite(spec.clearance_m) || spec.clearance_m < 0.0)
    return false;
  settings_ = &settings;
  geometry_ = &geometry;
  spec_ = spec;
  start_ = now.odometry;
  speed_mps_ =
      std::min(spec.speed_mps > 0.0 ? spec.speed_mps : settings.speed_mps, geometry.max_speed_mps);
  clearance_m_ = spec.clearance_m > 0.0 ? spec.clearance_m : settings.stopClearance();
  driven_m_ = 0.0;
  watch_.restart(now.time_s);
  contact_.restart();
  return true;
}

StepOutcome DrivePrimitive::step(const MotionInput& in, const SonarMemory& sonar) {
  StepOutcome out;
  const bool forward = spec_.distance_m > 0.0;
  driven_m_ = (in.odometry.position() - start_.position()).dot(start_.heading());
  const double remaining = std::abs(spec_.distance_m) - (forward ? driven_m_ : -driven_m_);
  if (remaining <= settings_->arrival_tolerance_m) {
    out.finish(ReportKind::kDone);
    return out;
  }
  if (forward && in.inContact()) {
    out.finish(ReportKind::kFailed, Reason::kBumped);
    return out;
  }
  if (!forward && contact_.blocked(in.inContact(), in.time_s, settings_->blocked_s)) {
    out.finish(ReportKind::kFailed, Reason::kBlocked);
    return out;
  }
  if (forward && spec_.stop_at_wall) {
    const auto front = sonar.frontDistance();
    if (front && *front < clearance_m_) {
      out.finish(ReportKind::kFrontWall);
      return out;
    }
  }
  if (watch_.stalled(remaining, 0.01, in.time_s, settings_->no_progress_s)) {
    out.finish(ReportKind::kFailed, Reason::kNoProgress);
    return out;
  }
  const double v =
      approachSpeed(remaining, geometry_->max_accel_mps2, settings_->min_speed_mps, speed_mps_);
  out.command = straightCommand(in.odometry.theta, start_.theta, forward ? v : -v);
  out.heading_rad = start_.theta;
  out.distance = StepOutcome::Distance{forward ? remaining : -remaining, speed_mps_};
  return out;
}

}  // namespace irgs::motion
