#pragma once
// The link protocol logic of the ground station side, pure: no Asio, no threads, no clock. The
// owner (comms/link/link.hpp, or a test with a fake clock) feeds it transport events, received
// frames and the time in seconds (`now_s`, monotonic), and drains what it produced with
// takeOutput(): messages to send, console events and finished commands.
//
// It sends HEARTBEAT every heartbeat_period_s while the transport is open, TIMESYNC requests
// every timesync_period_s while connected (the answer gives the round-trip time), answers the
// peer's TIMESYNC requests, tracks the connection state (docs/protocol.md, "Link state
// machine"), runs the command protocol (CommandManager) and keeps statistics.
//
// The peer is the first system whose HEARTBEAT is not from a ground station (MAV_TYPE_GCS) and
// not our own system id, or exactly `target_system` when that is set.

#include "comms/link/command_manager.hpp"
#include "comms/link/link_types.hpp"
#include "comms/link/rate_window.hpp"
#include "comms/mavlink/frame.hpp"
#include "comms/mavlink/frame_decoder.hpp"
#include "comms/mavlink/messages.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace irgs::comms {

struct LinkSessionConfig {
  std::uint8_t system_id = 255;     // ground station (docs/protocol.md, Identities)
  std::uint8_t component_id = 190;  // MAV_COMP_ID_MISSIONPLANNER
  // Our heartbeat: MAV_TYPE_GCS, MAV_AUTOPILOT_INVALID.
  mavlink::Heartbeat heartbeat{
      .type = static_cast<std::uint8_t>(mavlink::MavType::kGcs),
      .autopilot = static_cast<std::uint8_t>(mavlink::MavAutopilot::kInvalid),
      .system_status = static_cast<std::uint8_t>(mavlink::MavState::kActive)};
  double heartbeat_period_s = 1.0;
  double timeout_s = 1.5;          // no peer heartbeat for this long -> lost
  double timesync_period_s = 1.0;  // 0 disables TIMESYNC requests
  bool answer_timesync = true;     // reply to the peer's TIMESYNC requests
  double stats_window_s = 2.0;     // sliding window of the rates and loss %
  std::uint8_t target_system = 0;  // 0: lock on the first non-GCS heartbeat
  CommandConfig commands{};
};

// What the session asks its owner to send, encoded with our system/component id.
using SessionMessage = std::variant<mavlink::Heartbeat, mavlink::Timesync, mavlink::CommandLong>;

struct SessionOutput {
  std::vector<SessionMessage> messages;
  std::vector<LinkEvent> events;
  std::vector<CompletedCommand> completed;  // the owner invokes the callbacks
};

class LinkSession {
 public:
  // Throws std::invalid_argument for non-positive periods/timeouts (timesync may be 0).
  explicit LinkSession(LinkSessionConfig config = {});

  // ---- connection lifecycle (driven by the owner) ----
  // Disconnected -> Connecting (the owner starts opening the transport).
  void start(double now_s);
  // Closed by the user: -> Disconnected, pending commands cancelled.
  void close(double now_s);
  // Transport is open: heartbeats start (the first one at once).
  void onTransportOpen(double now_s, const std::string& description);
  // Transport failed or the peer went away: Connected -> Lost at once.
  void onTransportDown(double now_s, const std::string& reason);
  // The owner is reopening the transport (after a failure or a loss).
  void onReconnecting(double now_s, const std::string& reason);
  // Informational transport text ("listening on :5760").
  void onTransportStatus(double now_s, const std::string& text);

  // ---- traffic ----
  // Bytes handed to the decoder and the counters of that feed (for the error statistics).
  void onReceived(std::size_t bytes, const mavlink::DecodeCounters& delta, double now_s);
  void onFrame(const mavlink::Frame& frame, double now_s);
  // One message of `bytes` accepted by the transport (session output or the owner's own).
  void onSent(std::size_t bytes, double now_s);
  // Heartbeats, TIMESYNC, command retries, heartbeat timeout. Call often (every 50 ms or so).
  void tick(double now_s);

  // Starts the command protocol for `command`. target_system 0 is replaced by the peer's
  // system id (and then target_component 0 by the peer's component id) when a peer is known.
  void sendCommand(mavlink::CommandLong command, CommandCallback callback, double now_s);

  SessionOutput takeOutput();

  LinkState state() const { return state_; }
  bool transportOpen() const { return transport_open_; }
  // Whether takeOutput() would return console/state events (the owner delivers them at once, in
  // the byte stream's order: a link-up between two frames is seen between them).
  bool hasPendingEvents() const { return !output_.events.empty(); }
  LinkStats stats(double now_s) const;
  const LinkSessionConfig& config() const { return config_; }
  std::optional<mavlink::Heartbeat> peerHeartbeat() const { return peer_heartbeat_; }

 private:
  void setState(LinkState state, LinkEventKind kind, double now_s, std::uint8_t severity,
                std::string text);
  void event(LinkEventKind kind, double now_s, std::uint8_t severity, std::string text);
  void onHeartbeat(const mavlink::Frame& frame, const mavlink::Heartbeat& hb, double now_s);
  void onTimesync(const mavlink::Frame& frame, const mavlink::Timesync& ts, double now_s);
  void onStatusText(const mavlink::Frame& frame, const mavlink::Statustext& st, double now_s);
  void sendHeartbeat(double now_s);
  void collectCommands(double now_s);

  LinkSessionConfig config_;
  CommandManager commands_;
  LinkState state_ = LinkState::kDisconnected;
  bool transport_open_ = false;
  double next_heartbeat_s_ = 0.0;
  double next_timesync_s_ = 0.0;
  std::optional<double> last_peer_heartbeat_s_;
  std::optional<double> lost_since_s_;
  std::uint8_t peer_system_ = 0;
  std::uint8_t peer_component_ = 0;
  std::optional<mavlink::Heartbeat> peer_heartbeat_;

  // TIMESYNC requests in flight (ts1 in ns), oldest overwritten.
  std::array<std::optional<std::int64_t>, 4> timesync_sent_{};
  std::size_t timesync_next_slot_ = 0;
  std::optional<double> rtt_s_;
  std::optional<double> rtt_mean_s_;

  RateWindow rx_bytes_window_;
  RateWindow tx_bytes_window_;
  RateWindow rx_messages_window_;
  RateWindow tx_messages_window_;
  RateWindow frames_window_;  // frames the decoder delivered (loss denominator)
  RateWindow gaps_window_;    // frames missing by sequence numbers
  std::uint64_t rx_bytes_ = 0;
  std::uint64_t tx_bytes_ = 0;
  std::uint64_t rx_messages_ = 0;
  std::uint64_t tx_messages_ = 0;
  mavlink::DecodeCounters decode_totals_;
  std::uint32_t link_losses_ = 0;
  std::uint32_t reconnect_attempts_ = 0;

  SessionOutput output_;
};

}  // namespace irgs::comms
