#include "comms/link/link_session.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace irgs::comms {

namespace mav = mavlink;

std::string_view toString(LinkState state) {
  switch (state) {
    case LinkState::kDisconnected:
      return "disconnected";
    case LinkState::kConnecting:
      return "connecting";
    case LinkState::kConnected:
      return "connected";
    case LinkState::kLost:
      return "lost";
  }
  return "unknown";
}

std::string_view toString(CommandOutcome outcome) {
  switch (outcome) {
    case CommandOutcome::kAccepted:
      return "accepted";
    case CommandOutcome::kRejected:
      return "rejected";
    case CommandOutcome::kTimedOut:
      return "timed out";
    case CommandOutcome::kCancelled:
      return "cancelled";
  }
  return "unknown";
}

std::string_view toString(LinkEventKind kind) {
  switch (kind) {
    case LinkEventKind::kConnecting:
      return "connecting";
    case LinkEventKind::kLinkUp:
      return "link up";
    case LinkEventKind::kLinkLost:
      return "link lost";
    case LinkEventKind::kReconnecting:
      return "reconnecting";
    case LinkEventKind::kTransport:
      return "transport";
    case LinkEventKind::kClosed:
      return "closed";
    case LinkEventKind::kCommandResult:
      return "command result";
    case LinkEventKind::kStatusText:
      return "status text";
  }
  return "unknown";
}

namespace {

constexpr std::uint8_t kSeverityWarning = static_cast<std::uint8_t>(mav::MavSeverity::kWarning);
constexpr std::uint8_t kSeverityNotice = static_cast<std::uint8_t>(mav::MavSeverity::kNotice);
constexpr std::uint8_t kSeverityInfo = static_cast<std::uint8_t>(mav::MavSeverity::kInfo);
constexpr double kRttAlpha = 0.2;  // weight of the newest sample in rtt_mean_s

bool positive(double value) {
  return std::isfinite(value) && value > 0.0;
}

std::int64_t toNanoseconds(double seconds) {
  return static_cast<std::int64_t>(std::llround(seconds * 1e9));
}

std::string seconds(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.2f s", value);
  return buffer;
}

std::string sender(std::uint8_t system_id, std::uint8_t component_id) {
  return "system " + std::to_string(system_id) + ", component " + std::to_string(component_id);
}

}  // namespace

LinkSession::LinkSession(LinkSessionConfig config)
    : config_(config),
      commands_(config.commands),
      rx_bytes_window_(config.stats_window_s),
      tx_bytes_window_(config.stats_window_s),
      rx_messages_window_(config.stats_window_s),
      tx_messages_window_(config.stats_window_s),
      frames_window_(config.stats_window_s),
      gaps_window_(config.stats_window_s) {
  const bool timesync_ok =
      std::isfinite(config_.timesync_period_s) && config_.timesync_period_s >= 0.0;
  if (!positive(config_.heartbeat_period_s) || !positive(config_.timeout_s) || !timesync_ok)
    throw std::invalid_argument(
        "LinkSessionConfig: heartbeat_period_s and timeout_s must be > 0, timesync_period_s >= 0");
}

// ---------------------------------------------------------------- lifecycle

void LinkSession::start(double now_s) {
  if (state_ != LinkState::kDisconnected)
    return;
  setState(LinkState::kConnecting, LinkEventKind::kConnecting, now_s, kSeverityInfo, "connecting");
}

void LinkSession::close(double now_s) {
  transport_open_ = false;
  commands_.cancelAll("link closed", now_s);
  collectCommands(now_s);
  if (state_ != LinkState::kDisconnected)
    setState(LinkState::kDisconnected, LinkEventKind::kClosed, now_s, kSeverityInfo, "closed");
  last_peer_heartbeat_s_.reset();
  lost_since_s_.reset();
}

void LinkSession::onTransportOpen(double now_s, const std::string& description) {
  if (state_ == LinkState::kDisconnected)
    return;  // late notification after close()
  transport_open_ = true;
  event(LinkEventKind::kTransport, now_s, kSeverityInfo,
        description.empty() ? "transport open" : description);
  // Let the peer see us at once rather than up to one period later.
  sendHeartbeat(now_s);
}

void LinkSession::onTransportDown(double now_s, const std::string& reason) {
  transport_open_ = false;
  if (state_ == LinkState::kConnected) {
    ++link_losses_;
    lost_since_s_ = now_s;
    setState(LinkState::kLost, LinkEventKind::kLinkLost, now_s, kSeverityWarning,
             "link lost: " + reason);
  } else if (state_ != LinkState::kDisconnected) {
    event(LinkEventKind::kTransport, now_s, kSeverityWarning, reason);
  }
}

void LinkSession::onReconnecting(double now_s, const std::string& reason) {
  if (state_ == LinkState::kDisconnected)
    return;
  ++reconnect_attempts_;
  event(LinkEventKind::kReconnecting, now_s, kSeverityNotice,
        "reconnecting (attempt " + std::to_string(reconnect_attempts_) + "): " + reason);
}

void LinkSession::onTransportStatus(double now_s, const std::string& text) {
  if (state_ != LinkState::kDisconnected && !text.empty())
    event(LinkEventKind::kTransport, now_s, kSeverityInfo, text);
}

// ---------------------------------------------------------------- traffic

void LinkSession::onReceived(std::size_t bytes, const mav::DecodeCounters& delta, double now_s) {
  rx_bytes_ += bytes;
  rx_bytes_window_.add(now_s, static_cast<double>(bytes));
  decode_totals_ += delta;
  frames_window_.add(now_s, static_cast<double>(delta.frames));
  gaps_window_.add(now_s, static_cast<double>(delta.sequence_gaps));
}

void LinkSession::onFrame(const mav::Frame& frame, double now_s) {
  ++rx_messages_;
  rx_messages_window_.add(now_s, 1.0);
  if (state_ == LinkState::kDisconnected)
    return;
  if (frame.system_id == config_.system_id)
    return;  // our own traffic echoed back (UDP broadcast, a loopback cable)
  if (auto hb = frame.as<mav::Heartbeat>()) {
    onHeartbeat(frame, *hb, now_s);
  } else if (auto ts = frame.as<mav::Timesync>()) {
    onTimesync(frame, *ts, now_s);
  } else if (auto ack = frame.as<mav::CommandAck>()) {
    commands_.onAck(*ack, frame.system_id, config_.system_id, config_.component_id, now_s);
    collectCommands(now_s);
  } else if (auto st = frame.as<mav::Statustext>()) {
    onStatusText(frame, *st, now_s);
  }
}

void LinkSession::onSent(std::size_t bytes, double now_s) {
  tx_bytes_ += bytes;
  ++tx_messages_;
  tx_bytes_window_.add(now_s, static_cast<double>(bytes));
  tx_messages_window_.add(now_s, 1.0);
}

void LinkSession::tick(double now_s) {
  if (state_ == LinkState::kDisconnected)
    return;
  if (transport_open_ && now_s >= next_heartbeat_s_)
    sendHeartbeat(now_s);
  if (state_ == LinkState::kConnected && last_peer_heartbeat_s_ &&
      now_s - *last_peer_heartbeat_s_ > config_.timeout_s) {
    ++link_losses_;
    lost_since_s_ = now_s;
    setState(LinkState::kLost, LinkEventKind::kLinkLost, now_s, kSeverityWarning,
             "link lost: no heartbeat from " + sender(peer_system_, peer_component_) + " for " +
                 seconds(now_s - *last_peer_heartbeat_s_));
  }
  if (state_ == LinkState::kConnected && transport_open_ && config_.timesync_period_s > 0.0 &&
      now_s >= next_timesync_s_) {
    const std::int64_t ts1 = toNanoseconds(now_s);
    timesync_sent_[timesync_next_slot_] = ts1;
    timesync_next_slot_ = (timesync_next_slot_ + 1) % timesync_sent_.size();
    mav::Timesync request;
    request.tc1 = 0;
    request.ts1 = ts1;
    request.target_system = peer_system_;
    request.target_component = peer_component_;
    output_.messages.emplace_back(request);
    next_timesync_s_ = now_s + config_.timesync_period_s;
  }
  std::vector<mav::CommandLong> retries;
  commands_.tick(now_s, retries);
  for (const auto& c : retries)
    output_.messages.emplace_back(c);
  collectCommands(now_s);
}

void LinkSession::sendCommand(mav::CommandLong command, CommandCallback callback, double now_s) {
  if (command.target_system == 0 && peer_system_ != 0) {
    command.target_system = peer_system_;
    if (command.target_component == 0)
      command.target_component = peer_component_;
  }
  std::vector<mav::CommandLong> first;
  commands_.submit(command, std::move(callback), now_s, first);
  if (state_ == LinkState::kDisconnected) {
    // Nothing would ever retry or time it out: answer at once.
    commands_.cancelAll("link not open", now_s);
    first.clear();
  }
  for (const auto& c : first)
    output_.messages.emplace_back(c);
  collectCommands(now_s);  // a superseded command of the same id
}

SessionOutput LinkSession::takeOutput() {
  SessionOutput out;
  std::swap(out, output_);
  return out;
}

LinkStats LinkSession::stats(double now_s) const {
  LinkStats s;
  s.state = state_;
  s.rx_bytes_per_s = rx_bytes_window_.ratePerSecond(now_s);
  s.tx_bytes_per_s = tx_bytes_window_.ratePerSecond(now_s);
  s.rx_messages_per_s = rx_messages_window_.ratePerSecond(now_s);
  s.tx_messages_per_s = tx_messages_window_.ratePerSecond(now_s);
  s.rx_bytes = rx_bytes_;
  s.tx_bytes = tx_bytes_;
  s.rx_messages = rx_messages_;
  s.tx_messages = tx_messages_;
  s.crc_errors = decode_totals_.bad_crc;
  s.sequence_errors = decode_totals_.sequence_gaps;
  s.other_errors = decode_totals_.bad_length + decode_totals_.unknown_id +
                   decode_totals_.unsupported_flags + decode_totals_.bad_signature +
                   decode_totals_.replay_rejected + decode_totals_.unsigned_rejected;
  const double gaps = gaps_window_.sum(now_s);
  const double frames = frames_window_.sum(now_s);
  s.loss_percent = gaps + frames > 0.0 ? 100.0 * gaps / (gaps + frames) : 0.0;
  s.rtt_s = rtt_s_;
  s.rtt_mean_s = rtt_mean_s_;
  if (last_peer_heartbeat_s_)
    s.since_heartbeat_s = std::max(0.0, now_s - *last_peer_heartbeat_s_);
  s.link_losses = link_losses_;
  s.reconnect_attempts = reconnect_attempts_;
  s.peer_system_id = peer_system_;
  s.peer_component_id = peer_component_;
  return s;
}

// ---------------------------------------------------------------- private

void LinkSession::onHeartbeat(const mav::Frame& frame, const mav::Heartbeat& hb, double now_s) {
  if (hb.type == static_cast<std::uint8_t>(mav::MavType::kGcs))
    return;  // another ground station on a shared link is not our robot
  if (config_.target_system != 0 && frame.system_id != config_.target_system)
    return;
  const bool locked = state_ == LinkState::kConnected;
  if (locked && (frame.system_id != peer_system_ || frame.component_id != peer_component_))
    return;  // a second vehicle while connected to the first
  last_peer_heartbeat_s_ = now_s;
  peer_heartbeat_ = hb;
  if (locked)
    return;
  peer_system_ = frame.system_id;
  peer_component_ = frame.component_id;
  std::string text = "link up: " + sender(peer_system_, peer_component_) + " (MAV_TYPE " +
                     std::to_string(hb.type) + ")";
  if (lost_since_s_)
    text += ", was lost for " + seconds(now_s - *lost_since_s_);
  lost_since_s_.reset();
  next_timesync_s_ = now_s;  // measure the round trip at once
  setState(LinkState::kConnected, LinkEventKind::kLinkUp, now_s, kSeverityInfo, std::move(text));
}

void LinkSession::onTimesync(const mav::Frame& frame, const mav::Timesync& ts, double now_s) {
  if (ts.tc1 == 0) {
    // A request: answer with our clock, mirroring ts1, addressed to the requester.
    if (!config_.answer_timesync || !transport_open_)
      return;
    mav::Timesync reply;
    reply.tc1 = std::max<std::int64_t>(1, toNanoseconds(now_s));  // tc1 = 0 would be a request
    reply.ts1 = ts.ts1;
    reply.target_system = frame.system_id;
    reply.target_component = frame.component_id;
    output_.messages.emplace_back(reply);
    return;
  }
  if (ts.target_system != 0 && ts.target_system != config_.system_id)
    return;
  for (auto& slot : timesync_sent_) {
    if (slot && *slot == ts.ts1) {
      slot.reset();
      const double rtt = std::max(0.0, now_s - static_cast<double>(ts.ts1) * 1e-9);
      rtt_s_ = rtt;
      rtt_mean_s_ = rtt_mean_s_ ? (1.0 - kRttAlpha) * *rtt_mean_s_ + kRttAlpha * rtt : rtt;
      return;
    }
  }
}

void LinkSession::onStatusText(const mav::Frame& frame, const mav::Statustext& st, double now_s) {
  std::string text;
  for (char c : st.text) {
    if (c == '\0')
      break;
    const auto u = static_cast<unsigned char>(c);
    text.push_back(u < 0x20 || u == 0x7f ? '?' : c);  // keep UTF-8, drop control characters
  }
  event(LinkEventKind::kStatusText, now_s, std::min<std::uint8_t>(st.severity, 7),
        "[" + std::to_string(frame.system_id) + "] " + text);
}

void LinkSession::sendHeartbeat(double now_s) {
  output_.messages.emplace_back(config_.heartbeat);
  next_heartbeat_s_ = now_s + config_.heartbeat_period_s;
}

void LinkSession::collectCommands(double now_s) {
  for (auto& done : commands_.takeCompleted()) {
    const auto outcome = done.result.outcome;
    const std::uint8_t severity = outcome == CommandOutcome::kAccepted    ? kSeverityInfo
                                  : outcome == CommandOutcome::kCancelled ? kSeverityNotice
                                                                          : kSeverityWarning;
    LinkEvent e;
    e.kind = LinkEventKind::kCommandResult;
    e.time_s = now_s;
    e.state = state_;
    e.severity = severity;
    e.text = done.result.message;
    e.command = done.result;
    output_.events.push_back(std::move(e));
    output_.completed.push_back(std::move(done));
  }
}

void LinkSession::setState(LinkState state, LinkEventKind kind, double now_s, std::uint8_t severity,
                           std::string text) {
  state_ = state;
  event(kind, now_s, severity, std::move(text));
}

void LinkSession::event(LinkEventKind kind, double now_s, std::uint8_t severity, std::string text) {
  LinkEvent e;
  e.kind = kind;
  e.time_s = now_s;
  e.state = state_;
  e.severity = severity;
  e.text = std::move(text);
  output_.events.push_back(std::move(e));
}

}  // namespace irgs::comms
