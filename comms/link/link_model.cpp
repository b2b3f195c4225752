#include "comms/link/link_model.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace irgs::comms {

std::optional<std::string> linkModelConfigError(const LinkModelConfig& c) {
  const auto nonNegative = [](double v) { return std::isfinite(v) && v >= 0.0; };
  if (!nonNegative(c.delay_s) || !nonNegative(c.jitter_s) || !nonNegative(c.baud))
    return "delay, jitter and baud must be finite and >= 0";
  if (!nonNegative(c.stall_every_s) || !nonNegative(c.stall_s) || !nonNegative(c.stall_phase_s))
    return "stall period, length and phase must be finite and >= 0";
  if (c.stall_every_s > 0.0 && c.stall_s >= c.stall_every_s)
    return "a stall must be shorter than its period";
  if (!nonNegative(c.loss) || c.loss > 1.0 || !nonNegative(c.corruption) || c.corruption > 1.0)
    return "loss and corruption are probabilities in [0, 1]";
  return std::nullopt;
}

LinkModel::LinkModel(LinkModelConfig config) : config_(config), rng_(config.seed) {
  if (const auto error = linkModelConfigError(config_))
    throw std::invalid_argument("link model: " + *error);
}

double LinkModel::afterStalls(double t) const {
  if (config_.stall_every_s <= 0.0 || config_.stall_s <= 0.0)
    return t;
  const double start0 = config_.stall_every_s + config_.stall_phase_s;
  if (t < start0)
    return t;
  const double k = std::floor((t - start0) / config_.stall_every_s);
  const double stall_start = start0 + k * config_.stall_every_s;
  return t < stall_start + config_.stall_s ? stall_start + config_.stall_s : t;
}

void LinkModel::send(std::span<const std::uint8_t> bytes, double now_s) {
  if (bytes.empty())
    return;
  stats_.bytes_in += bytes.size();
  const double jitter = config_.jitter_s > 0.0 ? config_.jitter_s * unit_(rng_) : 0.0;
  const double byte_time = config_.baud > 0.0 ? 10.0 / config_.baud : 0.0;
  double line = std::max(line_free_s_, now_s);
  for (std::uint8_t b : bytes) {
    line += byte_time;
    // Both draws for every byte, so one probability does not shift the other's sequence.
    const double lose = unit_(rng_), flip = unit_(rng_);
    const auto bit = static_cast<int>(unit_(rng_) * 8.0);
    if (lose < config_.loss) {
      ++stats_.lost;
      continue;
    }
    if (flip < config_.corruption) {
      b = static_cast<std::uint8_t>(b ^ (1u << std::min(bit, 7)));
      ++stats_.corrupted;
    }
    // In order, and never faster than the far end's UART puts them out: bytes a stall or the
    // jitter held back come after it one byte time apart, not all at once.
    const double arrival =
        std::max(afterStalls(line + config_.delay_s + jitter), last_arrival_s_ + byte_time);
    last_arrival_s_ = arrival;
    queue_.push_back({arrival, b});
  }
  line_free_s_ = line;
}

std::vector<std::uint8_t> LinkModel::receive(double now_s) {
  std::vector<std::uint8_t> out;
  while (!queue_.empty() && queue_.front().arrival_s <= now_s) {
    out.push_back(queue_.front().byte);
    queue_.pop_front();
  }
  stats_.bytes_out += out.size();
  return out;
}

std::optional<double> LinkModel::nextArrival_s() const {
  if (queue_.empty())
    return std::nullopt;
  return queue_.front().arrival_s;
}

}  // namespace irgs::comms
