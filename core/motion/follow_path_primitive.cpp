#include "core/motion/follow_path_primitive.hpp"

#include <algorithm>
#include <cmath>

#include "core/motion/path_law.hpp"

namespace irgs::motion {
namespace {

constexpr double kTurnFirst_rad = degToRad(60.0);

}  // namespace

bool FollowPathPrimitive::start(const FollowPathSpec& spec, const MotionInput& now,
                                const MotionSettings& settings, const MotionGeometry& geometry) {
  if (spec.count == 0 || spec.count > kMaxWaypoints || !std::isfinite(spec.speed_mps) ||
      spec.speed_mps < 0.0)
    return false;
  for (std::size_t i = 0; i < spec.count; ++i)
    if (!std::isfinite(spec.points[i].x()) || !std::isfinite(spec.points[i].y()))
      return false;
  settings_ = &settings;
  geometry_ = &geometry;
  spec_ = spec;
  start_ = last_ = now.odometry.position();
  speed_mps_ =
      std::min(spec.speed_mps > 0.0 ? spec.speed_mps : settings.speed_mps, geometry.max_speed_mps);
  piece_ = 0;
  lateral_m_ = driven_m_ = 0.0;
  watch_.restart(now.time_s);
  return true;
}

StepOutcome FollowPathPrimitive::step(const MotionInput& in) {
  StepOutcome out;
  const Vec2 p = in.odometry.position();
  driven_m_ += (p - last_).norm();
  last_ = p;
  if (in.inContact()) {
    out.finish(ReportKind::kFailed, Reason::kBumped);
    return out;
  }
  // Pass every vertex the projection has gone beyond (pieces of zero length at once).
  Vec2 a, b;
  double along = 0.0, length = 0.0;
  for (;;) {
    a = piece_ == 0 ? start_ : spec_.points[static_cast<std::size_t>(piece_ - 1)];
    b = spec_.points[static_cast<std::size_t>(piece_)];
    length = (b - a).norm();
    along = length > 1e-9 ? (p - a).dot((b - a) / length) : 0.0;
    if (along < length - settings_->arrival_tolerance_m)
      break;
    out.add(ReportKind::kTurningPoint, Reason::kNone, static_cast<std::int16_t>(piece_));
    if (piece_ + 1 >= spec_.count) {
      out.finish(ReportKind::kDone);
      return out;
    }
    ++piece_;
    watch_.restart(in.time_s);
  }
  const Vec2 dir = (b - a) / length;
  lateral_m_ = cross(dir, p - a);  // > 0: left of the piece
  const double heading_error = wrapAngle(in.odometry.theta - std::atan2(dir.y(), dir.x()));
  if (watch_.stalled(length - along, 0.01, in.time_s, settings_->no_progress_s)) {
    out.finish(ReportKind::kFailed, Reason::kNoProgress);
    return out;
  }
  const double limit = std::min(settings_->turn_rate_radps, geometry_->max_turn_rate_radps);
  if (std::abs(heading_error) > kTurnFirst_rad) {
    out.command = {0.0, std::copysign(limit, -heading_error)};
    return out;
  }
  // Through the vertices at speed (the law takes the corner); braking only for the last one.
  const bool last = piece_ + 1 >= spec_.count;
  const double v = last ? approachSpeed(length - along, geometry_->max_accel_mps2,
                                        settings_->min_speed_mps, speed_mps_)
                        : speed_mps_;
  const PathLawOutput law =
      pathFollowingLaw(v, lateral_m_, heading_error, 0.0, settings_->path_k2, settings_->path_k3);
  out.command = {v, std::clamp(law.omega_radps, -limit, limit)};
  return out;
}

}  // namespace irgs::motion
