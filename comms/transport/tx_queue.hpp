#pragma once
// A byte-bounded FIFO of outgoing chunks. Not thread-safe: the owning transport locks it.

#include <cstddef>
#include <cstdint>
#include <deque>
#include <memory>
#include <span>
#include <vector>

namespace irgs::comms {

class TxQueue {
 public:
  using Chunk = std::shared_ptr<const std::vector<std::uint8_t>>;

  explicit TxQueue(std::size_t capacity_bytes) : capacity_bytes_(capacity_bytes) {}

  // Appends a copy unless that would exceed the capacity. An empty chunk is accepted and ignored.
  bool push(std::span<const std::uint8_t> bytes);
  // Removes and returns the oldest chunk; nullptr when empty. Its bytes stay counted in
  // bytes() until release() is called with its size (the chunk is then "in flight").
  Chunk pop();
  void release(std::size_t bytes);
  // Drops every waiting chunk and forgets in-flight bytes; returns the number of bytes dropped
  // (waiting ones only: in-flight bytes may still reach the wire).
  std::size_t clear();

  bool empty() const { return chunks_.empty(); }
  std::size_t bytes() const { return waiting_bytes_ + in_flight_bytes_; }
  std::size_t capacity() const { return capacity_bytes_; }

 private:
  std::size_t capacity_bytes_;
  std::size_t waiting_bytes_ = 0;
  std::size_t in_flight_bytes_ = 0;
  std::deque<Chunk> chunks_;
};

}  // namespace irgs::comms
