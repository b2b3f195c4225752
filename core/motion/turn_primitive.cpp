#include "core/motion/turn_primitive.hpp"

#include <algorithm>
#include <cmath>

#include "core/motion/position_revision.hpp"

namespace irgs::motion {

bool TurnPrimitive::start(const TurnSpec& spec, const MotionInput& now,
                          const MotionSettings& settings) {
  if (!std::isfinite(spec.angle_rad) || !std::isfinite(spec.quantum_rad) ||
      !std::isfinite(spec.rate_radps) || spec.quantum_rad < 0.0 || spec.rate_radps < 0.0)
    return false;
  settings_ = &settings;
  double angle = spec.absolute ? wrapAngle(spec.angle_rad - now.odometry.theta) : spec.angle_rad;
  angle = quantiseAngle(angle, spec.quantum_rad);
  angle_rad_ = angle;
  rate_radps_ = spec.rate_radps > 0.0 ? spec.rate_radps : settings.turn_rate_radps;
  turned_rad_ = 0.0;
  last_theta_ = now.odometry.theta;
  settling_ = false;
  progress_ = {};
  watch_.restart(now.time_s);
  contact_.restart();
  return true;
}

StepOutcome TurnPrimitive::step(const MotionInput& in) {
  StepOutcome out;
  turned_rad_ += wrapAngle(in.odometry.theta - last_theta_);
  last_theta_ = in.odometry.theta;
  const double remaining = angle_rad_ - turned_rad_;
  if (contact_.blocked(in.inContact(), in.time_s, settings_->blocked_s)) {
    out.finish(ReportKind::kFailed, Reason::kBlocked);
    return out;
  }
  if (watch_.stalled(std::abs(remaining), degToRad(0.5), in.time_s, settings_->no_progress_s)) {
    out.finish(ReportKind::kFailed, Reason::kNoProgress);
    return out;
  }
  if (!settling_ && std::abs(remaining) > 0.5 * kPi) {
    out.command = {0.0, std::copysign(rate_radps_, remaining)};
    return out;
  }
  if (!settling_) {
    settling_ = true;
    target_rad_ = wrapAngle(in.odometry.theta + remaining);
  }
  const TurnStep s = turnStep(progress_, in.odometry.theta, target_rad_, in.measured.angular_radps,
                              rate_radps_, settings_->heading_tolerance_rad);
  if (s.done) {
    out.finish(ReportKind::kDone);
    return out;
  }
  out.command = {0.0, s.angular_radps};
  out.heading_rad = target_rad_;
  return out;
}

}  // namespace irgs::motion
