#pragma once
// SEGMENTS: the traveling algorithm (003_… section 4.3, digest 4.10) run on the robot. From
// where it stands, for each waypoint in turn: turn on the spot toward it (the turn rounded to
// the spec's quantum, relative to the previous leg's heading as the host's makeTravelPlan
// does), then drive, steering at the waypoint, braking to arrive on it; a kTurningPoint report
// (index = waypoint) at each. Ends with kDone after the last, kFrontWall when something ahead
// lies before the waypoint within the clearance, kFailed(kBumped) on contact while driving,
// kFailed(kBlocked / kNoProgress) from the turn or the drive watchdog.

#include "core/motion/motion_input.hpp"
#include "core/motion/motion_settings.hpp"
#include "core/motion/sonar_memory.hpp"
#include "core/motion/turn_primitive.hpp"

namespace irgs::motion {

class SegmentsPrimitive {
 public:
  // False for no waypoint, a non-finite one, or a bad speed, quantum or clearance.
  bool start(const SegmentsSpec& spec, const MotionInput& now, const MotionSettings& settings,
             const MotionGeometry& geometry);
  StepOutcome step(const MotionInput& input, SonarMemory& sonar);
  int leg() const { return leg_; }
  double driven_m() const { return driven_m_; }

 private:
  void startLeg(int leg, const MotionInput& now);
  StepOutcome drive(const MotionInput& in, const SonarMemory& sonar);

  const MotionSettings* settings_ = nullptr;
  const MotionGeometry* geometry_ = nullptr;
  SegmentsSpec spec_;
  double speed_mps_ = 0.0;
  double clearance_m_ = 0.0;
  int leg_ = 0;
  bool turning_ = true;
  Vec2 from_ = Vec2::Zero();
  double leg_heading_rad_ = 0.0;  // heading of the current leg (quantised turn applied)
  double driven_m_ = 0.0;         // path length of the finished legs plus the current one
  double done_m_ = 0.0;
  TurnPrimitive turn_;
  ProgressWatch watch_;
};

}  // namespace irgs::motion
