#pragma once
// A linked robot as the session owns it. It keeps the IoThread alive until the robot (and with
// it its link) is destroyed — the session may outlive the window that created the link — and
// watches what reaches the session: sample times rebased to start at zero when connecting and to
// stay monotonic across robot reboots (the robot's clock is its boot time), and the odometry and
// sonar rates measured on the robot's own clock.

#include <cstdint>
#include <deque>
#include <memory>
#include <string>
#include <vector>

#include "comms/robot/linked_robot.hpp"
#include "comms/transport/io_thread.hpp"
#include "core/robot/robot.hpp"

namespace irgs::gui {

struct TelemetryRates {
  double odometry_hz = 0.0;  // samples per second (one per odometry message)
  double sonar_hz = 0.0;     // samples carrying at least one sonar reading, per second
  double sonar_readings_per_s = 0.0;
  std::uint64_t samples = 0;  // since connecting
  std::uint64_t sonar_readings = 0;
};

// The decoded-message sampling the GUI's linked robots ask for (LinkedRobotConfig::messages):
// every stream (message, or message instance) at up to 25 Hz — the full profile's 20 Hz
// streams whole, a replay at x16 thinned — for the plots' MAVLink fields.
comms::MessageSamplerConfig guiMessageSampling();

class LinkedRobotHandle final : public Robot {
 public:
  static constexpr double kRateWindow_s = 3.0;  // robot-clock window of the rates

  // `io` must be the thread `robot` was opened on.
  LinkedRobotHandle(std::shared_ptr<comms::IoThread> io, std::unique_ptr<comms::LinkedRobot> robot,
                    std::string url);
  ~LinkedRobotHandle() override;

  const RobotProfile& profile() const override { return robot_->profile(); }
  std::string describe() const override { return robot_->describe(); }
  void drive(const VelocityCommand& command) override { robot_->drive(command); }
  void stop() override { robot_->stop(); }
  std::vector<TelemetrySample> update(double wall_elapsed_s) override;
  std::vector<TelemetrySample> finish() override { return rebase(robot_->finish()); }

  comms::LinkedRobot& linked() { return *robot_; }
  const std::string& url() const { return url_; }
  TelemetryRates rates() const;
  // The robot's decoded messages (comms::LinkedRobot::takeMessages) with robot_time_s put on
  // the clock of the samples update() returns (rebased, reboots included), so a message and
  // the sample of its time stamp line up; messages stamped after a reboot the samples have not
  // shown yet are left out. Messages before the first sample wait for it (it sets the offset).
  std::vector<comms::MessageSample> takeMessages();
  static constexpr std::size_t kMaxEarlyMessages = 2048;

 private:
  // Puts the robot's samples on our monotonic clock (robot reboots included) and counts rates.
  std::vector<TelemetrySample> rebase(std::vector<TelemetrySample> samples);
  std::shared_ptr<comms::IoThread> io_;  // declared first: destroyed after the robot
  std::unique_ptr<comms::LinkedRobot> robot_;
  std::string url_;
  bool have_time_ = false;
  double last_robot_time_s_ = 0.0;     // robot clock of the previous sample
  double last_time_s_ = 0.0;           // rebased time of the previous sample
  std::deque<double> sample_times_s_;  // robot clock, within kRateWindow_s
  std::deque<double> sonar_times_s_;
  std::deque<std::pair<double, std::size_t>> sonar_counts_;
  std::uint64_t samples_ = 0;
  std::uint64_t sonar_readings_ = 0;
  std::vector<comms::MessageSample> early_messages_;  // taken before the first sample
};

}  // namespace irgs::gui
