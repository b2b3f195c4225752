#pragma once
// Value types of link management (see docs/protocol.md, "Link state machine"): the connection
// state, command results, console events and statistics. Plain structs so the GUI can copy them
// across threads.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace irgs::comms {

// kDisconnected: not started or closed by the user.
// kConnecting:   transport opening/open, no peer heartbeat seen yet in this session.
// kConnected:    a peer heartbeat arrived less than timeout_s ago.
// kLost:         was connected, then no heartbeat for timeout_s (or the transport failed); the
//                link keeps reconnecting until a heartbeat arrives again.
enum class LinkState { kDisconnected, kConnecting, kConnected, kLost };

std::string_view toString(LinkState state);

enum class CommandOutcome {
  kAccepted,   // COMMAND_ACK with MAV_RESULT_ACCEPTED
  kRejected,   // COMMAND_ACK with any other final MAV_RESULT (see mav_result)
  kTimedOut,   // no final COMMAND_ACK after every attempt (or after IN_PROGRESS expired)
  kCancelled,  // superseded by a newer command with the same id, or the link was closed
};

std::string_view toString(CommandOutcome outcome);

struct CommandResult {
  std::uint16_t command = 0;  // MAV_CMD
  CommandOutcome outcome = CommandOutcome::kTimedOut;
  std::optional<std::uint8_t> mav_result;  // MAV_RESULT of the final ack, if one arrived
  int attempts = 0;                        // COMMAND_LONG transmissions
  double elapsed_s = 0.0;                  // first transmission to the result
  std::string message;                     // one line for the console, e.g.
                                           // "IRGS_STOP accepted (1 attempt, 0.04 s)"
};

enum class LinkEventKind {
  kConnecting,     // transport opened, waiting for the peer's heartbeat
  kLinkUp,         // first heartbeat of the peer (or again after a loss)
  kLinkLost,       // heartbeat timeout or transport failure while connected
  kReconnecting,   // transport being reopened (after a failure or a loss)
  kTransport,      // transport status text (e.g. "listening on :5760", open errors)
  kClosed,         // closed by the user
  kCommandResult,  // a command finished (see `command`)
  kStatusText,     // STATUSTEXT from the peer (text, severity)
};

std::string_view toString(LinkEventKind kind);

struct LinkEvent {
  LinkEventKind kind = LinkEventKind::kTransport;
  double time_s = 0.0;                         // session clock
  LinkState state = LinkState::kDisconnected;  // state after the event
  std::uint8_t severity = 6;             // MAV_SEVERITY (0 emergency ... 7 debug), for colouring
  std::string text;                      // console line
  std::optional<CommandResult> command;  // kCommandResult only
};

struct LinkStats {
  LinkState state = LinkState::kDisconnected;
  // Sliding-window rates (window: LinkSessionConfig::stats_window_s).
  double rx_bytes_per_s = 0.0;
  double tx_bytes_per_s = 0.0;
  double rx_messages_per_s = 0.0;
  double tx_messages_per_s = 0.0;
  // What the link can carry towards the robot: baud / 10 bytes/s of the serial line behind it
  // (linkBaud of the URL); empty when unknown (TCP/UDP without a `baud` option).
  std::optional<double> tx_budget_bytes_per_s;
  // Totals since the session was created.
  std::uint64_t rx_bytes = 0;
  std::uint64_t tx_bytes = 0;
  std::uint64_t rx_messages = 0;
  std::uint64_t tx_messages = 0;
  std::uint64_t crc_errors = 0;       // decoder bad_crc
  std::uint64_t sequence_errors = 0;  // decoder sequence_gaps (frames missing)
  std::uint64_t other_errors = 0;     // bad length, unknown id, flags, signature, replay
  // Frames missing / (received + missing) over the window, in percent; 0 with no traffic.
  double loss_percent = 0.0;
  std::optional<double> rtt_s;              // last TIMESYNC round trip
  std::optional<double> rtt_mean_s;         // exponential average (alpha 0.2)
  std::optional<double> since_heartbeat_s;  // age of the last peer heartbeat
  std::uint32_t link_losses = 0;
  std::uint32_t reconnect_attempts = 0;
  std::uint8_t peer_system_id = 0;  // 0 until a peer heartbeat arrived
  std::uint8_t peer_component_id = 0;
};

}  // namespace irgs::comms
