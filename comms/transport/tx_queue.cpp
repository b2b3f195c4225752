#include "comms/transport/tx_queue.hpp"

#include <algorithm>

namespace irgs::comms {

bool TxQueue::push(std::span<const std::uint8_t> bytes) {
  if (bytes.empty())
    return true;
  if (bytes.size() > capacity_bytes_ || bytes.size() > capacity_bytes_ - this->bytes())
    return false;
  chunks_.push_back(std::make_shared<const std::vector<std::uint8_t>>(bytes.begin(), bytes.end()));
  waiting_bytes_ += bytes.size();
  return true;
}

TxQueue::Chunk TxQueue::pop() {
  if (chunks_.empty())
    return nullptr;
  Chunk chunk = std::move(chunks_.front());
  chunks_.pop_front();
  waiting_bytes_ -= chunk->size();
  in_flight_bytes_ += chunk->size();
  return chunk;
}

void TxQueue::release(std::size_t bytes) {
  in_flight_bytes_ -= std::min(bytes, in_flight_bytes_);
}

std::size_t TxQueue::clear() {
  const std::size_t dropped = waiting_bytes_;
  chunks_.clear();
  waiting_bytes_ = 0;
  in_flight_bytes_ = 0;
  return dropped;
}

}  // namespace irgs::comms
