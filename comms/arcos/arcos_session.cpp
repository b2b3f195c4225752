#include "comms/arcos/arcos_session.hpp"

#include <algorithm>
#include <cstdio>
#include <utility>

#include "comms/arcos/arcos_commands.hpp"

namespace irgs::comms::arcos {
namespace {
constexpr double kSyncRetryRoundTrips = 2.5;  // resend a SYNC only this many round trips on
constexpr double kMaxSyncRetry_s = 3.0;       // however slow the link looked
}  // namespace

const char* toString(ArcosState state) {
  switch (state) {
    case ArcosState::kDisconnected:
      return "disconnected";
    case ArcosState::kSyncing:
      return "syncing";
    case ArcosState::kOpening:
      return "opening";
    case ArcosState::kConnected:
      return "connected";
    case ArcosState::kLost:
      return "lost";
  }
  return "?";
}

ArcosClientSession::ArcosClientSession(ArcosSessionConfig config)
    : config_(config), sync_retry_s_(config.sync_retry_s), commands_(config.commands) {}

void ArcosClientSession::setState(ArcosState state, double now_s, std::string text, bool warning) {
  state_ = state;
  events_.push_back({now_s, state, warning, std::move(text)});
}

void ArcosClientSession::queue(std::vector<std::uint8_t> payload) {
  outgoing_.push_back(framePacket(payload));
}

void ArcosClientSession::start(double now_s) {
  identity_.reset();
  sync_retry_s_ = config_.sync_retry_s;
  beginSync(now_s);
}

void ArcosClientSession::beginSync(double now_s) {
  commands_.reset();  // nothing wanted on the old connection goes out on the new one
  sync_step_ = 0;
  sync_attempts_ = 0;
  setState(ArcosState::kSyncing, now_s, "ARCOS: synchronising (SYNC0)");
  sendSync(now_s);
}

void ArcosClientSession::sendSync(double now_s) {
  if (sync_attempts_ == 0)
    step_sent_s_ = now_s;
  queue(commandPayload(static_cast<std::uint8_t>(sync_step_)));
  last_sync_sent_s_ = now_s;
  ++sync_attempts_;
}

void ArcosClientSession::stop(double now_s) {
  if (state_ == ArcosState::kOpening || state_ == ArcosState::kConnected ||
      state_ == ArcosState::kLost) {
    queue(commandPayload(kClose));
  }
  commands_.reset();
  setState(ArcosState::kDisconnected, now_s, "ARCOS: closed");
}

void ArcosClientSession::sendCommand(std::vector<std::uint8_t> payload) {
  if (open())
    commands_.sendOnce(std::move(payload));
}

void ArcosClientSession::sendUrgent(Command command) {
  if (open())
    commands_.sendUrgent(command);
}

void ArcosClientSession::pump(double now_s) {
  if (!open())
    return;
  // The scheduler's gap lets at most one packet through per instant; the loop is for clarity.
  while (auto packet = commands_.next(now_s))
    outgoing_.push_back(std::move(*packet));
}

void ArcosClientSession::onPacket(const Packet& packet, double now_s) {
  if (state_ == ArcosState::kDisconnected)
    return;
  const std::span<const std::uint8_t> payload = packet.payload();
  const std::uint8_t type = packet.type();

  if (state_ == ArcosState::kSyncing) {
    if (isStandardSipType(type)) {
      // The robot still runs a previous connection: close it and synchronise again.
      queue(commandPayload(kClose));
      sync_step_ = 0;
      return;
    }
    if (type != sync_step_)
      return;  // a late echo of an earlier attempt
    // The round trip, at most (the echo may answer a resend): later SYNCs wait for it.
    sync_retry_s_ = std::max(
        sync_retry_s_, std::min(kMaxSyncRetry_s, kSyncRetryRoundTrips * (now_s - step_sent_s_)));
    if (sync_step_ < 2) {
      ++sync_step_;
      sync_attempts_ = 0;
      sendSync(now_s);
      return;
    }
    identity_ = parseSync2Reply(payload);
    if (!identity_)
      identity_ = RobotIdentity{};  // ARCOS allows an empty reply; carry on without names
    ++stats_.handshakes;
    // One command per packet, spaced by the scheduler: a server that gets them closer than a
    // few milliseconds may drop them (arcos_command_scheduler.hpp).
    commands_.reset();
    commands_.sendOnce(commandPayload(kOpen));
    if (config_.enable_motors)
      commands_.sendOnce(commandPayload(Command::kEnable, 1));
    commands_.sendOnce(commandPayload(Command::kSonar, config_.enable_sonar ? 1 : 0));
    opened_s_ = now_s;
    setState(ArcosState::kOpening, now_s,
             "ARCOS: robot \"" + identity_->name + "\" class " + identity_->robot_class +
                 " subclass " + identity_->subclass + "; opening");
    pump(now_s);
    return;
  }

  if (!isStandardSipType(type)) {
    ++stats_.other_packets;
    return;
  }
  SipParseResult parsed = parseStandardSip(payload);
  if (!parsed.sip) {
    ++stats_.bad_sips;
    events_.push_back({now_s, state_, true, "ARCOS: bad SIP skipped: " + parsed.error});
    return;
  }
  ++stats_.sips;
  stats_.last_sip_s = now_s;
  sips_.push_back(std::move(*parsed.sip));
  if (state_ == ArcosState::kOpening || state_ == ArcosState::kLost)
    setState(ArcosState::kConnected, now_s, "ARCOS: connected, receiving SIPs");
}

void ArcosClientSession::tick(double now_s) {
  switch (state_) {
    case ArcosState::kDisconnected:
      return;
    case ArcosState::kSyncing:
      if (now_s - last_sync_sent_s_ >= sync_retry_s_) {
        if (sync_attempts_ >= config_.max_sync_attempts) {
          events_.push_back({now_s, state_, true,
                             "ARCOS: no answer to SYNC" + std::to_string(sync_step_) +
                                 "; closing and starting over"});
          queue(commandPayload(kClose));
          sync_step_ = 0;
          sync_attempts_ = 0;
        }
        sendSync(now_s);
      }
      return;
    case ArcosState::kOpening:
    case ArcosState::kConnected: {
      pump(now_s);
      const double last = stats_.last_sip_s.value_or(opened_s_);
      if (now_s - std::max(last, opened_s_) >= config_.sip_timeout_s) {
        ++stats_.losses;
        char text[96];
        std::snprintf(text, sizeof text, "ARCOS: no SIP for %.1f s; link lost, resynchronising",
                      config_.sip_timeout_s);
        setState(ArcosState::kLost, now_s, text, true);
        beginSync(now_s);
      }
      return;
    }
    case ArcosState::kLost:
      return;
  }
}

std::vector<std::vector<std::uint8_t>> ArcosClientSession::takeOutgoing() {
  return std::exchange(outgoing_, {});
}
std::vector<StandardSip> ArcosClientSession::takeSips() {
  return std::exchange(sips_, {});
}
std::vector<ArcosEvent> ArcosClientSession::takeEvents() {
  return std::exchange(events_, {});
}

}  // namespace irgs::comms::arcos
