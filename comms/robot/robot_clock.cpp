#include "comms/robot/robot_clock.hpp"

#include <algorithm>

namespace irgs::comms {

double RobotClock::sampleTime(double robot_time_s) {
  restarted_ = false;
  if (!started_) {
    started_ = true;
    last_time_s_ = 0.0;
  } else if (robot_time_s < last_robot_time_s_ - kRestartJump_s) {
    restarted_ = true;
    last_time_s_ += kRestartStep_s;  // rebooted: keep our clock going
  } else {
    last_time_s_ += std::max(0.0, robot_time_s - last_robot_time_s_);
  }
  last_robot_time_s_ = robot_time_s;
  return last_time_s_;
}

std::optional<double> RobotClock::otherTime(double robot_time_s) const {
  if (!started_ || robot_time_s < last_robot_time_s_ - kRestartJump_s)
    return std::nullopt;
  // Samples advance last_time_s_ by the robot clock's steps: this is the offset of the clocks.
  return std::max(0.0, robot_time_s + (last_time_s_ - last_robot_time_s_));
}

}  // namespace irgs::comms
