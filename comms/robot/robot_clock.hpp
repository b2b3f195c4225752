#pragma once
// Puts a robot's time stamps on a clock that starts at zero with the first sample and never
// runs backwards. A MAVLink robot stamps its messages with its boot time, which starts over when
// it reboots: a step back by more than kRestartJump_s is taken as a reboot, and the clock
// continues kRestartStep_s after the last sample. Data that travels beside the samples (decoded
// messages, reports) is put on the same clock with the offset the samples set.

#include <optional>

namespace irgs::comms {

class RobotClock {
 public:
  // A robot-clock step backwards by more than this is a reboot (the clock restarted at zero).
  static constexpr double kRestartJump_s = 0.5;
  // The spacing given to the first sample after a reboot on our clock.
  static constexpr double kRestartStep_s = 0.05;

  // Our time of the sample stamped `robot_time_s` (samples in arrival order). Sets restarted().
  double sampleTime(double robot_time_s);
  // True when the last sampleTime() call saw a reboot.
  bool restarted() const { return restarted_; }
  // True once a sample set the offset of the clocks.
  bool started() const { return started_; }
  // Our time of something else the robot stamped `robot_time_s`, with the offset of the last
  // sample; nullopt before the first sample and for a time stamped after a reboot the samples
  // have not shown yet (it would land far in the past). Never negative.
  std::optional<double> otherTime(double robot_time_s) const;
  // Our time of the newest sample (0 before any).
  double lastTime_s() const { return last_time_s_; }

 private:
  bool started_ = false;
  bool restarted_ = false;
  double last_robot_time_s_ = 0.0;  // robot clock of the previous sample
  double last_time_s_ = 0.0;        // our time of the previous sample
};

}  // namespace irgs::comms
