#pragma once
// The MAVLink robot (comms::LinkedRobot) as a RemoteRobot: its samples put on a clock that
// starts at zero and survives reboots (RobotClock), the rates measured on the robot's clock,
// its decoded messages on the samples' clock, its parameters and behaviour commands, and the
// final stop confirmed by IRGS_STOP's COMMAND_ACK.

#include <atomic>
#include <memory>
#include <string>
#include <vector>

#include "comms/robot/remote_robot.hpp"
#include "comms/robot/robot_clock.hpp"

namespace irgs::comms {

class MavlinkRemoteRobot final : public RemoteRobot,
                                 public FirmwareParameters,
                                 public MessageStream,
                                 public BehaviourCommands,
                                 public MotionControl {
 public:
  static constexpr std::size_t kMaxEarlyMessages = 2048;

  // `io` (may be a non-owning pointer) must be the thread `robot` was opened on.
  MavlinkRemoteRobot(std::shared_ptr<IoThread> io, std::unique_ptr<LinkedRobot> robot,
                     std::string url);
  ~MavlinkRemoteRobot() override;

  // Robot
  const RobotProfile& profile() const override { return robot_->profile(); }
  std::string describe() const override { return robot_->describe(); }
  void drive(const VelocityCommand& command) override { robot_->drive(command); }
  void stop() override { robot_->stop(); }
  std::vector<TelemetrySample> update(double wall_elapsed_s) override;
  std::vector<TelemetrySample> finish() override;

  // RemoteRobot
  std::string_view protocol() const override { return "mavlink"; }
  const std::string& url() const override { return url_; }
  std::string linkLabel() const override { return url_; }  // the panel adds the system id
  LinkState linkState() const override { return robot_->linkState(); }
  LinkStats linkStats() const override { return robot_->linkStats(); }
  std::vector<LinkEvent> takeEvents() override { return robot_->takeEvents(); }
  std::uint64_t droppedSamples() const override { return robot_->droppedSamples(); }
  TelemetryRates telemetryRates() const override { return rates_.rates(); }
  void requestConfirmedStop() override;
  std::optional<bool> stopConfirmed() const override;
  FirmwareParameters* firmwareParameters() override { return this; }
  MessageStream* messageStream() override { return this; }
  BehaviourCommands* behaviourCommands() override { return this; }
  MotionControl* motionControl() override { return this; }

  // MotionControl: the firmware's primitives, their reports put on the samples' clock.
  bool supports(motion::PrimitiveKind kind) const override;
  void start(const motion::Primitive& primitive) override;
  void cancel() override;
  std::vector<motion::MotionReport> takeReports() override;

  // FirmwareParameters
  void requestParams() override { robot_->requestParams(); }
  void setParam(const std::string& name, double value) override { robot_->setParam(name, value); }
  std::vector<ParamEntry> firmwareParams() const override { return robot_->firmwareParams(); }
  int firmwareParamCount() const override { return robot_->firmwareParamCount(); }
  bool readingParams() const override { return robot_->readingParams(); }
  std::vector<ParamWriteResult> takeParamResults() override { return robot_->takeParamResults(); }

  // MessageStream
  std::vector<MessageSample> takeMessages() override;

  // BehaviourCommands
  void sendBehaviour(const RobotBehaviourCommand& command, CommandCallback done = {}) override {
    robot_->sendBehaviour(command, std::move(done));
  }

 private:
  // Puts the robot's samples on our clock and counts their rates.
  std::vector<TelemetrySample> rebase(std::vector<TelemetrySample> samples);

  // Shared with the stop's ack callback, which runs on the io thread and may outlive us.
  struct StopAnswer {
    std::atomic<bool> answered{false};
    std::atomic<bool> accepted{false};
  };

  std::shared_ptr<IoThread> io_;  // declared first: destroyed after the robot
  std::unique_ptr<LinkedRobot> robot_;
  std::string url_;
  RobotClock clock_;
  TelemetryRateMeter rates_;
  std::vector<MessageSample> early_messages_;  // taken before the first sample
  std::shared_ptr<StopAnswer> stop_answer_ = std::make_shared<StopAnswer>();
  bool stop_sent_ = false;
};

}  // namespace irgs::comms
