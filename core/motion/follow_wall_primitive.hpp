#pragma once
// FOLLOW_WALL: the wall follower (wall_follow.hpp, revisions (a)-(d)) with the stop conditions
// and reports the host needs: a kMode report at every change of the follower's mode (the host
// knows when the robot is beside a wall, turning or seeking), kContact at a bumper, a
// kDistanceMark every report_every_m of path; it ends with kDone at the travel limit, with
// kWallLost when the follower gives the wall up (stop_when_lost), with kFrontWall at a wall
// ahead instead of turning (stop_at_front_wall).

#include <optional>

#include "core/motion/motion_input.hpp"
#include "core/motion/motion_settings.hpp"
#include "core/motion/wall_follow.hpp"

namespace irgs::motion {

class FollowWallPrimitive {
 public:
  // False for a bad distance, speed or limit, or a robot without the sonars for that side.
  bool start(const FollowWallSpec& spec, const MotionInput& now, const MotionSettings& settings,
             const MotionGeometry& geometry);
  StepOutcome step(const MotionInput& input);
  double driven_m() const { return control_ ? control_->distanceTravelled_m() : 0.0; }
  // The follower (present once started).
  const std::optional<WallFollowControl>& control() const { return control_; }

 private:
  FollowWallSpec spec_;
  std::optional<WallFollowControl> control_;
  WallFollowMode mode_ = WallFollowMode::kSeek;
  double next_mark_m_ = 0.0;
};

// The follower's config for a spec: the robot's defaults with the spec's side, distance and
// speed (capped by the robot's limits), the valid distance beyond the set distance.
WallFollowConfig followConfigFor(const FollowWallSpec& spec, const MotionSettings& settings,
                                 const MotionGeometry& geometry);

}  // namespace irgs::motion
