#pragma once
// A robot at the far end of a link, whatever the protocol: MAVLink (comms::LinkedRobot, the
// IRGS firmware and irgs-robot) or ARCOS/P2OS (comms::ArcosRobot: Pioneers, MobileSim,
// `irgs-robot --protocol arcos`), chosen by the URL's protocol option. It is an irgs::Robot whose
// remoteRobot() capability returns itself, so the GUI and irgs-sim reach the link without
// knowing the protocol (docs/decisions/robot-capabilities.md):
//   - link state, statistics and console events (link events and the robot's own texts);
//   - telemetry rates measured on the robot's clock;
//   - a confirmed stop:
//       MAVLink  zero MANUAL_CONTROL + IRGS_STOP, confirmed by its COMMAND_ACK (accepted);
//       ARCOS    STOP, confirmed when a later SIP reports both wheels at rest (|v| < 1 mm/s,
//                |omega| < 0.1 deg/s): ARCOS acknowledges no command, the SIP is its answer;
//   - optional capabilities, null where the protocol has none: firmware parameters, the
//     decoded message stream (the plots' fields), behaviour commands (MAVLink has all three,
//     ARCOS none of them).
// Sample times start at zero with the first sample and never run backwards (a MAVLink robot's
// boot clock starts over when it reboots; RobotClock). The robot keeps its IoThread alive (when
// opened with a shared one) until it is destroyed. Not thread-safe: one caller thread (the
// IoThread works underneath).

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "comms/link/command_manager.hpp"
#include "comms/link/link_types.hpp"
#include "comms/link/link_url.hpp"
#include "comms/robot/arcos_robot.hpp"
#include "comms/robot/linked_robot.hpp"
#include "comms/robot/message_sampler.hpp"
#include "comms/robot/param_client.hpp"
#include "comms/robot/telemetry_rates.hpp"
#include "comms/transport/io_thread.hpp"
#include "core/robot/robot.hpp"

namespace irgs::comms {

// The robot's firmware parameters (MAVLink parameter protocol, param_client.hpp): read all,
// write one (confirmed by the robot's answer). The answers are read with firmwareParams() and
// takeParamResults().
class FirmwareParameters {
 public:
  virtual ~FirmwareParameters() = default;
  virtual void requestParams() = 0;
  // Throws std::invalid_argument for a bad name or a non-finite value (nothing is sent).
  virtual void setParam(const std::string& name, double value) = 0;
  virtual std::vector<ParamEntry> firmwareParams() const = 0;
  virtual int firmwareParamCount() const = 0;  // what the robot announced (0 before any)
  virtual bool readingParams() const = 0;
  virtual std::vector<ParamWriteResult> takeParamResults() = 0;
};

// The robot's decoded messages, every numeric field, thinned per stream (message_sampler.hpp).
class MessageStream {
 public:
  virtual ~MessageStream() = default;
  // Oldest first, robot_time_s on the clock of the samples update() returns, so a message and
  // the sample of its time stamp line up. Messages before the first sample wait for it.
  virtual std::vector<MessageSample> takeMessages() = 0;
};

// Behaviours the robot's firmware runs on command (move a distance, turn an angle, ...).
class BehaviourCommands {
 public:
  virtual ~BehaviourCommands() = default;
  // Acknowledged and retried by the link; the result arrives as a kCommandResult link event
  // (and through `done`, on the io thread). Throws std::invalid_argument for an invalid command
  // before sending anything.
  virtual void sendBehaviour(const RobotBehaviourCommand& command, CommandCallback done = {}) = 0;
};

class RemoteRobot : public Robot {
 public:
  RemoteRobot* remoteRobot() final { return this; }

  virtual std::string_view protocol() const = 0;  // "mavlink" or "arcos"
  // The URL this robot was opened with (or the name given for it, e.g. a replay's).
  virtual const std::string& url() const = 0;
  // The link as the link-health panel names it: the URL, with the robot at the far end when the
  // protocol says who it is without a heartbeat of its own (ARCOS: the SYNC2 name).
  virtual std::string linkLabel() const = 0;
  virtual LinkState linkState() const = 0;
  virtual LinkStats linkStats() const = 0;
  virtual std::vector<LinkEvent> takeEvents() = 0;  // oldest first
  virtual std::uint64_t droppedSamples() const = 0;
  virtual TelemetryRates telemetryRates() const = 0;

  // Sends the final stop (see the file comment). Idempotent.
  virtual void requestConfirmedStop() = 0;
  // True once the stop was confirmed, false when the robot refused it, empty while waiting.
  virtual std::optional<bool> stopConfirmed() const = 0;

  // Optional capabilities of the link.
  virtual FirmwareParameters* firmwareParameters() { return nullptr; }
  virtual MessageStream* messageStream() { return nullptr; }
  virtual BehaviourCommands* behaviourCommands() { return nullptr; }
};

struct RemoteRobotConfig {
  LinkedRobotConfig mavlink{};  // used when the URL speaks MAVLink
  ArcosRobotConfig arcos{};     // used when it says protocol=arcos
  std::string name;             // what url() reports; empty: the URL's text
};

struct OpenRemoteRobotResult {
  std::unique_ptr<RemoteRobot> robot;  // null when error is set
  std::string error;
};

// Opens the robot the URL names (it connects, and reconnects, on its own from then on), keeping
// `io` alive until the robot is destroyed.
OpenRemoteRobotResult openRemoteRobot(std::shared_ptr<IoThread> io, const LinkUrl& url,
                                      const RobotProfile& profile, RemoteRobotConfig config = {});
// The same on an IoThread the caller keeps alive for longer than the robot.
OpenRemoteRobotResult openRemoteRobot(IoThread& io, const LinkUrl& url, const RobotProfile& profile,
                                      RemoteRobotConfig config = {});

}  // namespace irgs::comms
