#include "comms/robot/teleop_pacer.hpp"

#include <cmath>
#include <stdexcept>

namespace irgs::comms {

namespace {
constexpr double kEpsilon_s = 1e-9;  // a deadline met up to rounding is met
}  // namespace

TeleopPacer::TeleopPacer(TeleopPacerConfig config) : config_(config) {
  if (!std::isfinite(config_.min_interval_s) || !std::isfinite(config_.repeat_period_s) ||
      !(config_.min_interval_s > 0.0) || config_.min_interval_s > config_.repeat_period_s)
    throw std::invalid_argument("TeleopPacer: need 0 < min_interval_s <= repeat_period_s");
}

void TeleopPacer::want(const TeleopAxes& axes) {
  if (axes == wanted_)
    return;
  if (pending_)
    ++stats_.coalesced;
  wanted_ = axes;
  // Nothing to say before the first motion; back to what went out last: nothing new to say.
  pending_ = sent_ ? !(axes == *sent_) : !axes.zero();
}

void TeleopPacer::cancel() {
  if (pending_)
    ++stats_.coalesced;
  wanted_ = {};
  pending_ = false;
  if (sent_)
    sent_ = TeleopAxes{};
}

std::optional<TeleopAxes> TeleopPacer::next(double now_s) {
  if (now_s - last_sent_s_ < config_.min_interval_s - kEpsilon_s)
    return std::nullopt;
  const bool repeat = !pending_ && sent_ && !sent_->zero() &&
                      now_s - last_sent_s_ >= config_.repeat_period_s - kEpsilon_s;
  if (!pending_ && !repeat)
    return std::nullopt;
  stats_.repeats += repeat ? 1 : 0;
  ++stats_.sent;
  pending_ = false;
  sent_ = wanted_;
  last_sent_s_ = now_s;
  return wanted_;
}

}  // namespace irgs::comms
