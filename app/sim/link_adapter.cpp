#include "app/sim/link_adapter.hpp"

#include <atomic>
#include <cmath>
#include <utility>

#include "comms/robot/arcos_robot.hpp"
#include "comms/robot/linked_robot.hpp"

namespace irgs::app {
namespace {

class MavlinkAdapter final : public LinkAdapter {
 public:
  explicit MavlinkAdapter(std::unique_ptr<comms::LinkedRobot> robot) : robot_(std::move(robot)) {}

  Robot& robot() override { return *robot_; }
  std::string_view protocol() const override { return "mavlink"; }
  comms::LinkState linkState() const override { return robot_->linkState(); }
  comms::LinkStats linkStats() const override { return robot_->linkStats(); }
  std::vector<comms::LinkEvent> takeEvents() override { return robot_->takeEvents(); }
  std::uint64_t droppedSamples() const override { return robot_->droppedSamples(); }
  std::vector<TelemetrySample> update() override { return robot_->update(0.0); }

  void requestStop() override {
    robot_->drive({});
    if (stop_sent_)
      return;
    stop_sent_ = true;
    robot_->sendBehaviour({.kind = comms::RobotBehaviourKind::kStop},
                          [flags = flags_](const comms::CommandResult& r) {
                            flags->accepted = r.outcome == comms::CommandOutcome::kAccepted;
                            flags->answered = true;
                          });
  }
  std::optional<bool> stopConfirmed() const override {
    if (!flags_->answered)
      return std::nullopt;
    return flags_->accepted.load();
  }

 private:
  // Shared with the ack callback, which runs on the io thread and may outlive a request.
  struct Flags {
    std::atomic<bool> answered{false};
    std::atomic<bool> accepted{false};
  };
  std::shared_ptr<Flags> flags_ = std::make_shared<Flags>();
  std::unique_ptr<comms::LinkedRobot> robot_;
  bool stop_sent_ = false;
};

class ArcosAdapter final : public LinkAdapter {
 public:
  explicit ArcosAdapter(std::unique_ptr<comms::ArcosRobot> robot) : robot_(std::move(robot)) {}

  Robot& robot() override { return *robot_; }
  std::string_view protocol() const override { return "arcos"; }
  comms::LinkState linkState() const override { return robot_->linkState(); }
  comms::LinkStats linkStats() const override { return robot_->linkStats(); }
  std::vector<comms::LinkEvent> takeEvents() override { return robot_->takeEvents(); }
  std::uint64_t droppedSamples() const override { return robot_->droppedSamples(); }

  std::vector<TelemetrySample> update() override {
    auto samples = robot_->update(0.0);
    if (stop_sent_ && !at_rest_)
      for (const TelemetrySample& s : samples)
        // Wheel speeds come in whole mm/s and rotation in 0.1 deg/s: below those is zero.
        if (std::abs(s.measured_velocity.linear_mps) < 1e-3 &&
            std::abs(s.measured_velocity.angular_radps) < degToRad(0.1))
          at_rest_ = true;
    return samples;
  }
  void requestStop() override {
    if (stop_sent_)
      return;
    stop_sent_ = true;
    robot_->stop();
  }
  std::optional<bool> stopConfirmed() const override {
    return at_rest_ ? std::optional<bool>(true) : std::nullopt;
  }

 private:
  std::unique_ptr<comms::ArcosRobot> robot_;
  bool stop_sent_ = false;
  bool at_rest_ = false;
};

}  // namespace

OpenLinkResult openLinkAdapter(comms::IoThread& io, const comms::LinkUrl& url,
                               const RobotProfile& profile,
                               std::optional<comms::mavlink::SigningKey> signing_key) {
  OpenLinkResult out;
  if (comms::isArcosUrl(url)) {
    if (signing_key) {
      out.error = "a signing key is MAVLink's: ARCOS has no signing";
      return out;
    }
    auto opened = comms::ArcosRobot::open(io, url, profile);
    if (opened.robot)
      out.adapter = std::make_unique<ArcosAdapter>(std::move(opened.robot));
    else
      out.error = std::move(opened.error);
    return out;
  }
  comms::LinkedRobotConfig config;
  config.link.signing_key = signing_key;
  config.link.require_signed = signing_key.has_value();
  auto opened = comms::LinkedRobot::open(io, url, profile, std::move(config));
  if (opened.robot)
    out.adapter = std::make_unique<MavlinkAdapter>(std::move(opened.robot));
  else
    out.error = std::move(opened.error);
  return out;
}

}  // namespace irgs::app
