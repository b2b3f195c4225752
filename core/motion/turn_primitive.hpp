#pragma once
// TURN: an on-the-spot turn by an angle (any size, a full scan turn included) or to a heading,
// optionally in quanta. Far from the target the robot turns at the set rate; within a quarter
// turn it hands over to turnStep (turn_control.hpp), which brakes and settles on the target.

#include "core/motion/motion_input.hpp"
#include "core/motion/motion_settings.hpp"
#include "core/motion/turn_control.hpp"

namespace irgs::motion {

class TurnPrimitive {
 public:
  // False (nothing started) for a non-finite angle, quantum or rate.
  bool start(const TurnSpec& spec, const MotionInput& now, const MotionSettings& settings);
  StepOutcome step(const MotionInput& input);
  double turned_rad() const { return turned_rad_; }

 private:
  const MotionSettings* settings_ = nullptr;
  double angle_rad_ = 0.0;  // signed, relative to the start heading
  double rate_radps_ = 0.0;
  double turned_rad_ = 0.0;  // signed, integrated from the odometry heading
  double last_theta_ = 0.0;
  bool settling_ = false;  // within a quarter turn: turnStep on a fixed target heading
  double target_rad_ = 0.0;
  TurnProgress progress_;
  ProgressWatch watch_;
  ContactWatch contact_;
};

}  // namespace irgs::motion
