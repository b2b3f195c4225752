#pragma once
// The MAVLink command protocol (https://mavlink.io/en/services/command.html), pure: COMMAND_LONG
// is (re)transmitted every retry_s until a matching COMMAND_ACK arrives or max_attempts
// transmissions went unanswered. Retransmissions carry confirmation = 1, 2, ...
// MAV_RESULT_IN_PROGRESS stops the retransmissions and waits up to in_progress_timeout_s for the
// final ack (each further IN_PROGRESS restarts that wait). One command per MAV_CMD id is in
// flight, as the protocol requires: submitting the same id again cancels the older one.
// Time is the caller's (seconds, monotonic); nothing here blocks or reads a clock.

#include "comms/link/link_types.hpp"
#include "comms/mavlink/messages.hpp"

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace irgs::comms {

struct CommandConfig {
  double retry_s = 0.5;  // between transmissions without an ack
  int max_attempts = 4;  // first transmission + 3 retries (docs/protocol.md)
  double in_progress_timeout_s = 30.0;
};

using CommandCallback = std::function<void(const CommandResult&)>;

struct CompletedCommand {
  CommandResult result;
  CommandCallback callback;  // may be empty
};

// "IRGS_MOVE_DISTANCE", "COMPONENT_ARM_DISARM", ... or "MAV_CMD 1234" for an unnamed id.
std::string commandName(std::uint16_t command);
// "ACCEPTED", "DENIED", ... or "MAV_RESULT 42".
std::string resultName(std::uint8_t result);

class CommandManager {
 public:
  // Throws std::invalid_argument for a non-positive retry_s/in_progress_timeout_s or
  // max_attempts < 1.
  explicit CommandManager(CommandConfig config = {});

  // Starts `command` (its confirmation field is overwritten). The first transmission is appended
  // to `out` at once.
  void submit(mavlink::CommandLong command, CommandCallback callback, double now_s,
              std::vector<mavlink::CommandLong>& out);
  // A COMMAND_ACK from (system_id, component_id); `own_system`/`own_component` are ours, for the
  // ack's optional target fields. Returns true when it matched a pending command.
  bool onAck(const mavlink::CommandAck& ack, std::uint8_t system_id, std::uint8_t own_system,
             std::uint8_t own_component, double now_s);
  // Retransmissions into `out`; finished commands are collected for takeCompleted().
  void tick(double now_s, std::vector<mavlink::CommandLong>& out);
  // Ends every pending command as cancelled with `reason`.
  void cancelAll(const std::string& reason, double now_s);

  std::vector<CompletedCommand> takeCompleted();
  std::size_t pending() const { return pending_.size(); }
  const CommandConfig& config() const { return config_; }

 private:
  struct Pending {
    mavlink::CommandLong command;
    CommandCallback callback;
    double first_sent_s = 0.0;
    double next_action_s = 0.0;  // next retransmission, or the in-progress deadline
    int attempts = 0;
    bool in_progress = false;
  };
  void finish(std::size_t index, CommandOutcome outcome, std::optional<std::uint8_t> result,
              std::string detail, double now_s);

  CommandConfig config_;
  std::vector<Pending> pending_;
  std::vector<CompletedCommand> completed_;
};

}  // namespace irgs::comms
