#include "comms/arcos/arcos_command_scheduler.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "comms/arcos/arcos_packet.hpp"

namespace irgs::comms::arcos {

namespace {

// Times come from a clock sampled by the owner's tick: a deadline met up to rounding is met.
constexpr double kEpsilon_s = 1e-9;
constexpr double kBitsPerByte = 10.0;  // start + 8 data + stop bits on the UART
constexpr double kWireShare = 0.5;     // commands may take at most half the link's bytes/s

std::size_t indexOf(MotionSlot slot) {
  return static_cast<std::size_t>(slot);
}

SlotCommand zeroOf(MotionSlot slot) {
  return slot == MotionSlot::kTranslational ? SlotCommand{Command::kVel, 0}
                                            : SlotCommand{Command::kRVel, 0};
}

}  // namespace

std::optional<MotionSlot> slotOf(Command command) {
  switch (command) {
    case Command::kVel:
    case Command::kMove:
      return MotionSlot::kTranslational;
    case Command::kRVel:
    case Command::kHead:
    case Command::kDHead:
      return MotionSlot::kRotational;
    default:
      return std::nullopt;
  }
}

bool isRepeatable(Command command) {
  return command == Command::kVel || command == Command::kRVel || command == Command::kHead;
}

ArcosCommandScheduler::ArcosCommandScheduler(ArcosCommandSchedulerConfig config) : config_(config) {
  const auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  if (config_.max_packets < 1 || config_.burst < 1 || config_.burst > config_.max_packets ||
      !positive(config_.window_s) || !positive(config_.min_gap_s) || config_.baud == 0 ||
      !positive(config_.keepalive_s) || !positive(config_.refresh_s))
    throw std::invalid_argument(
        "ArcosCommandScheduler: cap, burst (<= cap), window, gap, baud and keep-alive periods "
        "must be > 0");
  tokens_ = config_.burst;
}

void ArcosCommandScheduler::want(const SlotCommand& command) {
  const std::optional<MotionSlot> slot = slotOf(command.command);
  if (!slot)
    throw std::invalid_argument("ArcosCommandScheduler::want: command " +
                                std::to_string(static_cast<int>(command.command)) +
                                " is not a motion command");
  if (command.argument < -kMaxIntArgument || command.argument > kMaxIntArgument)
    throw std::invalid_argument("ArcosCommandScheduler::want: argument out of range: " +
                                std::to_string(command.argument));
  Slot& s = slots_[indexOf(*slot)];
  const bool repeatable = isRepeatable(command.command);
  if (repeatable && s.sent == command) {
    // Wanted back before the change went out: nothing to send.
    if (s.pending) {
      s.pending.reset();
      ++stats_.coalesced;
    }
    return;
  }
  if (s.pending) {
    if (repeatable && *s.pending == command)
      return;
    ++stats_.coalesced;  // the newest wins; the slot keeps its place in the line
  } else {
    s.pending_order = ++order_;
  }
  s.pending = command;
  stop_in_effect_ = false;
}

void ArcosCommandScheduler::sendOnce(std::vector<std::uint8_t> payload) {
  if (payload.empty() || payload.size() > kMaxPayload)
    throw std::invalid_argument("ArcosCommandScheduler::sendOnce: payload must be 1.." +
                                std::to_string(kMaxPayload) + " bytes");
  one_shots_.push_back(std::move(payload));
}

void ArcosCommandScheduler::sendUrgent(Command command) {
  if (command != Command::kStop && command != Command::kEStop)
    throw std::invalid_argument("ArcosCommandScheduler::sendUrgent: STOP or ESTOP only");
  std::vector<std::uint8_t> payload = commandPayload(command);
  if ((command == Command::kStop && stop_in_effect_) ||
      std::find(urgent_.begin(), urgent_.end(), payload) != urgent_.end()) {
    ++stats_.coalesced;
    return;
  }
  urgent_.push_back(std::move(payload));
  stop_in_effect_ = true;
  // Both stops leave the robot's set points at zero: a change waiting to go is superseded.
  for (MotionSlot slot : {MotionSlot::kTranslational, MotionSlot::kRotational}) {
    Slot& s = slots_[indexOf(slot)];
    if (s.pending) {
      s.pending.reset();
      ++stats_.coalesced;
    }
    s.sent = zeroOf(slot);
  }
}

void ArcosCommandScheduler::reset() {
  slots_ = {};
  urgent_.clear();
  one_shots_.clear();
  stop_in_effect_ = false;
  tokens_ = config_.burst;
  started_ = false;
  recent_s_.clear();
  last_sent_s_ = -1e300;
  last_bytes_ = 0;
}

std::optional<SlotCommand> ArcosCommandScheduler::wanted(MotionSlot slot) const {
  const Slot& s = slots_[indexOf(slot)];
  return s.pending ? s.pending : s.sent;
}

bool ArcosCommandScheduler::idle() const {
  return urgent_.empty() && one_shots_.empty() && !slots_[0].pending && !slots_[1].pending;
}

double ArcosCommandScheduler::gapAfterLast() const {
  const double wire_s = static_cast<double>(last_bytes_) * kBitsPerByte / config_.baud;
  return std::max(config_.min_gap_s, wire_s / kWireShare);
}

double ArcosCommandScheduler::gapLeft(double now_s) const {
  return std::max(0.0, last_sent_s_ + gapAfterLast() - now_s);
}

bool ArcosCommandScheduler::capAllows(double now_s) const {
  if (now_s - last_sent_s_ < gapAfterLast() - kEpsilon_s)
    return false;
  std::size_t in_window = 0;
  for (double t : recent_s_)
    in_window += now_s - t < config_.window_s - kEpsilon_s ? 1 : 0;
  return in_window < static_cast<std::size_t>(config_.max_packets);
}

void ArcosCommandScheduler::refill(double now_s) {
  if (now_s > refilled_s_) {
    const double rate = config_.max_packets / config_.window_s;
    tokens_ = std::min<double>(config_.burst, tokens_ + (now_s - refilled_s_) * rate);
    refilled_s_ = now_s;
  }
}

std::vector<std::uint8_t> ArcosCommandScheduler::issue(std::vector<std::uint8_t> payload,
                                                       double now_s, bool bucket) {
  // An urgent stop is not held by the bucket but pays for itself: the next packets wait.
  tokens_ = bucket ? tokens_ - 1.0 : std::max(tokens_ - 1.0, -static_cast<double>(config_.burst));
  std::vector<std::uint8_t> packet = framePacket(payload);
  recent_s_.push_back(now_s);
  while (recent_s_.size() > static_cast<std::size_t>(config_.max_packets))
    recent_s_.pop_front();
  last_sent_s_ = now_s;
  last_bytes_ = packet.size();
  ++stats_.packets;
  stats_.bytes += packet.size();
  return packet;
}

std::vector<std::uint8_t> ArcosCommandScheduler::sendSlot(Slot& slot, const SlotCommand& command,
                                                          double now_s) {
  slot.sent = command;
  slot.pending.reset();
  slot.last_sent_s = now_s;
  return issue(commandPayload(command.command, command.argument), now_s, true);
}

std::optional<std::vector<std::uint8_t>> ArcosCommandScheduler::nextSlotChange(double now_s) {
  Slot* oldest = nullptr;
  for (Slot& s : slots_) {
    if (s.pending && (oldest == nullptr || s.pending_order < oldest->pending_order))
      oldest = &s;
  }
  if (oldest == nullptr)
    return std::nullopt;
  ++stats_.changes;
  return sendSlot(*oldest, *oldest->pending, now_s);
}

std::optional<std::vector<std::uint8_t>> ArcosCommandScheduler::nextKeepAlive(double now_s) {
  Slot* oldest = nullptr;  // the repeatable slot sent longest ago
  for (Slot& s : slots_) {
    if (s.sent && isRepeatable(s.sent->command) &&
        (oldest == nullptr || s.last_sent_s < oldest->last_sent_s))
      oldest = &s;
  }
  const bool refresh_due =
      oldest != nullptr && now_s - oldest->last_sent_s >= config_.refresh_s - kEpsilon_s;
  const bool keepalive_due =
      now_s - std::max(last_sent_s_, started_s_) >= config_.keepalive_s - kEpsilon_s;
  if (refresh_due || (keepalive_due && oldest != nullptr)) {
    ++stats_.refreshes;
    return sendSlot(*oldest, *oldest->sent, now_s);
  }
  if (keepalive_due) {
    ++stats_.pulses;
    return issue(commandPayload(kPulse), now_s, true);
  }
  return std::nullopt;
}

std::optional<std::vector<std::uint8_t>> ArcosCommandScheduler::next(double now_s) {
  if (!started_) {
    started_ = true;
    started_s_ = now_s;
    refilled_s_ = now_s;
  }
  refill(now_s);
  if (!capAllows(now_s))
    return std::nullopt;
  if (!urgent_.empty()) {
    std::vector<std::uint8_t> payload = std::move(urgent_.front());
    urgent_.pop_front();
    ++stats_.urgent;
    for (Slot& s : slots_)
      s.last_sent_s = now_s;  // the stop carried both zero set points
    return issue(std::move(payload), now_s, false);
  }
  if (tokens_ < 1.0 - kEpsilon_s)
    return std::nullopt;
  if (!one_shots_.empty()) {
    std::vector<std::uint8_t> payload = std::move(one_shots_.front());
    one_shots_.pop_front();
    ++stats_.one_shots;
    return issue(std::move(payload), now_s, true);
  }
  if (auto change = nextSlotChange(now_s))
    return change;
  return nextKeepAlive(now_s);
}

}  // namespace irgs::comms::arcos
