#pragma once
// FOLLOW_PATH: path following of paper 004 (digest 5.6) along a polyline from where the robot
// stands through the waypoints, with the law of path_law.hpp on each straight piece (c = 0):
// the lateral offset l and heading error theta~ decay while the robot keeps moving. Far off
// the piece's direction (over 60 degrees, e.g. at the start) it first turns on the spot. A
// kTurningPoint report (index = waypoint) as the projection passes each vertex; kDone past
// the last; kFailed(kBumped) on contact; kFailed(kNoProgress) from the watchdog.

#include "core/motion/motion_input.hpp"
#include "core/motion/motion_settings.hpp"

namespace irgs::motion {

class FollowPathPrimitive {
 public:
  // False for no waypoint, a non-finite one, or a bad speed.
  bool start(const FollowPathSpec& spec, const MotionInput& now, const MotionSettings& settings,
             const MotionGeometry& geometry);
  StepOutcome step(const MotionInput& input);
  int piece() const { return piece_; }
  double lateral_m() const { return lateral_m_; }  // l on the current piece, left positive
  double driven_m() const { return driven_m_; }

 private:
  const MotionSettings* settings_ = nullptr;
  const MotionGeometry* geometry_ = nullptr;
  FollowPathSpec spec_;
  Vec2 start_ = Vec2::Zero();
  double speed_mps_ = 0.0;
  int piece_ = 0;  // from (piece 0: the start, else waypoint piece-1) to waypoint `piece`
  double lateral_m_ = 0.0;
  double driven_m_ = 0.0;
  Vec2 last_ = Vec2::Zero();
  ProgressWatch watch_;
};

}  // namespace irgs::motion
