#include "core/motion/follow_wall_primitive.hpp"

#include <algorithm>
#include <cmath>

namespace irgs::motion {

WallFollowConfig followConfigFor(const FollowWallSpec& spec, const MotionSettings& settings,
                                 const MotionGeometry& geometry) {
  WallFollowConfig c = settings.follow;
  c.wall_on_left = spec.wall_on_left;
  c.distance_m = spec.distance_m;
  c.speed_mps =
      std::min(spec.speed_mps > 0.0 ? spec.speed_mps : c.speed_mps, geometry.max_speed_mps);
  c.turn_rate_radps = std::min(c.turn_rate_radps, geometry.max_turn_rate_radps);
  c.valid_distance_m = std::max(c.valid_distance_m, c.distance_m + c.lost_margin_m + 0.1);
  return c;
}

bool FollowWallPrimitive::start(const FollowWallSpec& spec, const MotionInput& now,
                                const MotionSettings& settings, const MotionGeometry& geometry) {
  if (!std::isfinite(spec.distance_m) || spec.distance_m <= 0.0 || !std::isfinite(spec.speed_mps) ||
      spec.speed_mps < 0.0 || !std::isfinite(spec.travel_limit_m) || spec.travel_limit_m < 0.0 ||
      !std::isfinite(spec.report_every_m) || spec.report_every_m < 0.0)
    return false;
  const WallFollowConfig config = followConfigFor(spec, settings, geometry);
  if (!WallFollowControl::usable(geometry, config))
    return false;
  spec_ = spec;
  control_.emplace(geometry, config);
  mode_ = control_->mode();
  next_mark_m_ = spec.report_every_m;
  (void)now;
  return true;
}

StepOutcome FollowWallPrimitive::step(const MotionInput& in) {
  StepOutcome out;
  out.command = control_->step(in);
  out.heading_rad = control_->headingSetpoint();
  const WallFollowEvent event = control_->event();
  if (event == WallFollowEvent::kWallAhead && spec_.stop_at_front_wall) {
    out.finish(ReportKind::kFrontWall);
    return out;
  }
  if (event == WallFollowEvent::kLost && spec_.stop_when_lost) {
    out.finish(ReportKind::kWallLost);
    return out;
  }
  if (event == WallFollowEvent::kBumper)
    out.add(ReportKind::kContact);
  if (control_->mode() != mode_) {
    mode_ = control_->mode();
    out.add(ReportKind::kMode, Reason::kNone, static_cast<std::int16_t>(mode_));
  }
  const double driven = control_->distanceTravelled_m();
  if (spec_.report_every_m > 0.0 && driven >= next_mark_m_) {
    out.add(ReportKind::kDistanceMark);
    next_mark_m_ += spec_.report_every_m;
  }
  if (spec_.travel_limit_m > 0.0 && driven >= spec_.travel_limit_m)
    out.finish(ReportKind::kDone);
  return out;
}

}  // namespace irgs::motion
