#pragma once
// The ARCOS robot (comms::ArcosRobot) as a RemoteRobot: its link, rates and events as they are
// (its samples are stamped on its own clock since open(), which never runs backwards), its
// motion primitives when it has them, and the final stop confirmed by the first SIP that shows
// the wheels at rest. ARCOS has no firmware parameters, message stream or behaviour commands
// of the kind the GUI's panels show: those capabilities are null.

#include <memory>
#include <string>
#include <vector>

#include "comms/robot/remote_robot.hpp"

namespace irgs::comms {

class ArcosRemoteRobot final : public RemoteRobot {
 public:
  // Wheel speeds come in whole mm/s and rotation in 0.1 deg/s: below those is at rest.
  static constexpr double kRestSpeed_mps = 1e-3;
  static constexpr double kRestTurnRate_degps = 0.1;

  ArcosRemoteRobot(std::unique_ptr<ArcosRobot> robot, std::string url);

  // Robot
  const RobotProfile& profile() const override { return robot_->profile(); }
  std::string describe() const override { return robot_->describe(); }
  void drive(const VelocityCommand& command) override { robot_->drive(command); }
  void stop() override { robot_->stop(); }
  std::vector<TelemetrySample> update(double wall_elapsed_s) override;
  std::vector<TelemetrySample> finish() override { return robot_->finish(); }
  MotionControl* motionControl() override { return robot_->motionControl(); }

  // RemoteRobot
  std::string_view protocol() const override { return "arcos"; }
  const std::string& url() const override { return url_; }
  std::string linkLabel() const override { return robot_->describe(); }
  LinkState linkState() const override { return robot_->linkState(); }
  LinkStats linkStats() const override { return robot_->linkStats(); }
  std::vector<LinkEvent> takeEvents() override { return robot_->takeEvents(); }
  std::uint64_t droppedSamples() const override { return robot_->droppedSamples(); }
  TelemetryRates telemetryRates() const override;
  void requestConfirmedStop() override;
  std::optional<bool> stopConfirmed() const override;

 private:
  std::unique_ptr<ArcosRobot> robot_;  // keeps its IoThread alive when opened with a shared one
  std::string url_;
  bool stop_sent_ = false;
  bool at_rest_ = false;
};

}  // namespace irgs::comms
