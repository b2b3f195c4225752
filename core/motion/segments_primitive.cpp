#include "core/motion/segments_primitive.hpp"

#include <algorithm>
#include <cmath>

#include "core/motion/position_revision.hpp"

namespace irgs::motion {
namespace {

// Closer than this to the waypoint the heading hold keeps the leg direction instead of aiming
// at the point (whose bearing swings as the robot passes it).
constexpr double kAimMinDistance_m = 0.05;
constexpr double kStopMargin_m = 0.02;  // beyond the body's front extent, for the sonar stop
constexpr double kSameWaypoint_m = 1e-3;

}  // namespace

bool SegmentsPrimitive::start(const SegmentsSpec& spec, const MotionInput& now,
                              const MotionSettings& settings, const MotionGeometry& geometry) {
  if (spec.count == 0 || spec.count > kMaxWaypoints || !std::isfinite(spec.speed_mps) ||
      spec.speed_mps < 0.0 || !std::isfinite(spec.quantum_rad) || spec.quantum_rad < 0.0 ||
      !std::isfinite(spec.clearance_m) || spec.clearance_m < 0.0)
    return false;
  for (std::size_t i = 0; i < spec.count; ++i)
    if (!std::isfinite(spec.points[i].x()) || !std::isfinite(spec.points[i].y()))
      return false;
  settings_ = &settings;
  geometry_ = &geometry;
  spec_ = spec;
  speed_mps_ =
      std::min(spec.speed_mps > 0.0 ? spec.speed_mps : settings.speed_mps, geometry.max_speed_mps);
  clearance_m_ = spec.clearance_m > 0.0 ? spec.clearance_m : settings.stopClearance();
  driven_m_ = done_m_ = 0.0;
  from_ = now.odometry.position();
  leg_heading_rad_ = now.odometry.theta;
  startLeg(0, now);
  return true;
}

void SegmentsPrimitive::startLeg(int leg, const MotionInput& now) {
  leg_ = leg;
  turning_ = true;
  const Vec2 to = spec_.points[static_cast<std::size_t>(leg)];
  const Vec2 d = to - from_;
  if (d.norm() > kSameWaypoint_m) {
    const double turn =
        quantiseAngle(wrapAngle(std::atan2(d.y(), d.x()) - leg_heading_rad_), spec_.quantum_rad);
    leg_heading_rad_ = wrapAngle(leg_heading_rad_ + turn);
  }
  TurnSpec spec;
  spec.angle_rad = leg_heading_rad_;
  spec.absolute = true;
  turn_.start(spec, now, *settings_);
  watch_.restart(now.time_s);
}

StepOutcome SegmentsPrimitive::step(const MotionInput& in, SonarMemory& sonar) {
  driven_m_ = done_m_ + (in.odometry.position() - from_).norm();
  if (!turning_)
    return drive(in, sonar);
  // A waypoint on top of the previous one: reached at once.
  if ((spec_.points[static_cast<std::size_t>(leg_)] - from_).norm() <= kSameWaypoint_m) {
    turning_ = false;
    return drive(in, sonar);
  }
  StepOutcome out = turn_.step(in);
  if (!out.finished)
    return out;
  if (out.notes[0].kind != ReportKind::kDone)
    return out;  // the turn failed: so does the run
  turning_ = false;
  sonar.forgetBefore(in.time_s);  // after a turn the sonars look elsewhere
  watch_.restart(in.time_s);
  return {};
}

StepOutcome SegmentsPrimitive::drive(const MotionInput& in, const SonarMemory& sonar) {
  StepOutcome out;
  const Vec2 to = spec_.points[static_cast<std::size_t>(leg_)];
  const Vec2 p = in.odometry.position();
  const Vec2 leg = to - from_;
  const Vec2 dir = leg.norm() > kSameWaypoint_m
                       ? Vec2(leg.normalized())
                       : Vec2(std::cos(leg_heading_rad_), std::sin(leg_heading_rad_));
  const double remaining = (to - p).dot(dir);
  if (remaining <= settings_->arrival_tolerance_m) {
    out.add(ReportKind::kTurningPoint, Reason::kNone, static_cast<std::int16_t>(leg_));
    done_m_ += leg.norm();
    from_ = to;
    if (leg_ + 1 >= spec_.count) {
      out.finish(ReportKind::kDone);
      return out;
    }
    startLeg(leg_ + 1, in);
    return out;
  }
  if (in.inContact()) {
    out.finish(ReportKind::kFailed, Reason::kBumped);
    return out;
  }
  if (spec_.stop_at_wall) {
    const auto front = sonar.frontDistance();
    if (front && *front < clearance_m_ &&
        (spec_.stop_beyond_waypoint ||
         *front < remaining + geometry_->front_extent_m + kStopMargin_m)) {
      out.finish(ReportKind::kFrontWall);
      return out;
    }
  }
  if (watch_.stalled(remaining, 0.01, in.time_s, settings_->no_progress_s)) {
    out.finish(ReportKind::kFailed, Reason::kNoProgress);
    return out;
  }
  const Vec2 to_target = to - p;
  const double aim = to_target.norm() > kAimMinDistance_m ? std::atan2(to_target.y(), to_target.x())
                                                          : std::atan2(dir.y(), dir.x());
  const double heading_error = wrapAngle(aim - in.odometry.theta);
  const double limit = std::min(settings_->turn_rate_radps, geometry_->max_turn_rate_radps);
  const double omega = std::clamp(settings_->heading_gain * heading_error, -limit, limit);
  double v =
      approachSpeed(remaining, geometry_->max_accel_mps2, settings_->min_speed_mps, speed_mps_);
  // Far off the leg direction (a disturbed robot), turn first rather than sweep sideways.
  v *= std::max(0.0, std::cos(heading_error));
  out.command = {v, omega};
  out.heading_rad = aim;
  out.distance = StepOutcome::Distance{remaining, speed_mps_};
  return out;
}

}  // namespace irgs::motion
