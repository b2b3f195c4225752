#include "comms/robot/message_sampler.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace irgs::comms {

MessageSampler::MessageSampler(MessageSamplerConfig config) : config_(config) {
  if (!std::isfinite(config_.max_rate_hz) || config_.max_rate_hz < 0.0)
    throw std::invalid_argument("message sampler: max_rate_hz must be finite and >= 0");
  if (enabled() && !(config_.burst >= 1.0 && std::isfinite(config_.burst)))
    throw std::invalid_argument("message sampler: burst must be finite and >= 1");
}

void MessageSampler::onFrame(const mavlink::Frame& frame, double now_s) {
  if (!enabled())
    return;
  const mavlink::MessageFields* message = mavlink::findMessageFields(frame.message_id);
  if (message == nullptr) {
    ++counters_.unknown;
    return;
  }
  // The clock first, so untimed messages thinned away still see the newest time stamp.
  const std::optional<double> stamp_s = mavlink::timeStamp_s(*message, frame);
  if (stamp_s) {
    if (newest_time_s_ && *stamp_s < *newest_time_s_ - kRestartJump_s) {
      ++counters_.restarts;
      newest_time_s_ = *stamp_s;
    } else {
      newest_time_s_ = std::max(newest_time_s_.value_or(*stamp_s), *stamp_s);
    }
    // What arrived before the first time stamp sits at it.
    for (MessageSample& waiting : untimed_) {
      waiting.robot_time_s = *newest_time_s_;
      push(std::move(waiting));
    }
    untimed_.clear();
  }

  std::optional<std::uint32_t> instance;
  if (const auto index = mavlink::instanceField(*message))
    instance = static_cast<std::uint32_t>(mavlink::readField(message->fields[*index], frame));
  const std::uint64_t stream =
      (static_cast<std::uint64_t>(frame.message_id) << 32) | instance.value_or(0xFFFFFFFFu);
  if (!admit(stream, now_s)) {
    ++counters_.thinned;
    return;
  }

  MessageSample sample;
  sample.message = message;
  sample.instance = instance;
  sample.values.reserve(message->fields.size());
  for (const mavlink::FieldInfo& field : message->fields)
    sample.values.push_back(mavlink::readField(field, frame));
  if (stamp_s) {
    sample.robot_time_s = *stamp_s;
  } else if (newest_time_s_) {
    sample.robot_time_s = *newest_time_s_;
  } else {
    ++counters_.untimed;
    untimed_.push_back(std::move(sample));
    if (untimed_.size() > kMaxUntimed) {
      untimed_.pop_front();
      ++counters_.dropped;
    }
    return;
  }
  push(std::move(sample));
}

void MessageSampler::push(MessageSample sample) {
  pending_.push_back(std::move(sample));
  ++counters_.kept;
  while (pending_.size() > std::max<std::size_t>(1, config_.max_pending)) {
    pending_.pop_front();
    ++counters_.dropped;
  }
}

bool MessageSampler::admit(std::uint64_t stream, double now_s) {
  // A new stream starts with a full bucket; tokens refill at max_rate_hz up to `burst`.
  auto [it, added] = buckets_.try_emplace(stream, Bucket{config_.burst, now_s});
  Bucket& bucket = it->second;
  if (!added) {
    const double elapsed_s = std::max(0.0, now_s - bucket.last_s);
    bucket.tokens = std::min(config_.burst, bucket.tokens + elapsed_s * config_.max_rate_hz);
    bucket.last_s = now_s;
  }
  if (bucket.tokens < 1.0)
    return false;
  bucket.tokens -= 1.0;
  return true;
}

void MessageSampler::reset() {
  newest_time_s_.reset();
}

std::vector<MessageSample> MessageSampler::take() {
  std::vector<MessageSample> out(std::make_move_iterator(pending_.begin()),
                                 std::make_move_iterator(pending_.end()));
  pending_.clear();
  return out;
}

}  // namespace irgs::comms
