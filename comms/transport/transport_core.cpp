#include "comms/transport/transport_core.hpp"

#include <boost/asio/error.hpp>
#include <boost/asio/post.hpp>

#include <future>

namespace irgs::comms {

std::string_view toString(TransportState state) {
  switch (state) {
    case TransportState::kClosed:
      return "closed";
    case TransportState::kOpening:
      return "opening";
    case TransportState::kOpen:
      return "open";
    case TransportState::kFailed:
      return "failed";
  }
  return "unknown";
}

namespace detail {

TransportCore::TransportCore(IoThread& io, std::size_t tx_capacity_bytes, std::string description,
                             TransportCallbacks callbacks)
    : io_(io),
      description_(std::move(description)),
      callbacks_(std::make_shared<const TransportCallbacks>(std::move(callbacks))),
      queue_(tx_capacity_bytes) {}

void TransportCore::requestOpen() {
  boost::asio::post(io(), [self = shared_from_this()] { self->openNow(); });
}

void TransportCore::requestClose() {
  boost::asio::post(io(), [self = shared_from_this()] { self->closeNow(); });
}

void TransportCore::shutdown() {
  // Forget the callbacks first: the owner is being destroyed and must not hear "closed".
  auto finish = [this] {
    callbacks_.reset();
    closeNow();
  };
  if (io_.isCurrentThread() || !io_.running()) {
    finish();
    return;
  }
  std::promise<void> done;
  boost::asio::post(io(), [&] {
    finish();
    done.set_value();
  });
  done.get_future().wait();
}

TransportStats TransportCore::stats() const {
  TransportStats s;
  s.rx_bytes = rx_bytes_.load();
  s.refused_peers = refused_peers_.load();
  const std::lock_guard lock(mutex_);
  s.tx_bytes = tx_bytes_;
  s.tx_dropped_bytes = tx_dropped_bytes_;
  s.tx_queued_bytes = queue_.bytes();
  return s;
}

bool TransportCore::send(std::span<const std::uint8_t> bytes) {
  const bool usable = state_.load() == TransportState::kOpen && readyToSend();
  std::uint64_t gen = 0;
  {
    const std::lock_guard lock(mutex_);
    if (!usable || !queue_.push(bytes)) {
      tx_dropped_bytes_ += bytes.size();
      return false;
    }
    if (write_in_flight_ || queue_.empty())
      return true;
    write_in_flight_ = true;
    gen = generation_;
  }
  boost::asio::post(io(), [self = shared_from_this(), gen] { self->kickWrite(gen); });
  return true;
}

void TransportCore::kickWrite(std::uint64_t gen) {
  {
    const std::lock_guard lock(mutex_);
    if (gen != generation_)
      return;  // that session's queue was already discarded
    if (state_.load() != TransportState::kOpen) {
      // Queued in the instant the link went down: discard.
      tx_dropped_bytes_ += queue_.clear();
      write_in_flight_ = false;
      return;
    }
  }
  writeNext();
}

void TransportCore::writeNext() {
  TxQueue::Chunk chunk;
  std::uint64_t gen = 0;
  {
    const std::lock_guard lock(mutex_);
    chunk = queue_.pop();
    if (!chunk) {
      write_in_flight_ = false;
      in_flight_size_ = 0;
      return;
    }
    in_flight_size_ = chunk->size();
    gen = generation_;
  }
  doWrite(gen, std::move(chunk));
}

void TransportCore::writeDone(std::uint64_t gen, const boost::system::error_code& ec,
                              std::size_t written) {
  if (!current(gen) || ec == boost::asio::error::operation_aborted)
    return;
  if (ec) {
    fail("write failed on " + description_ + ": " + ec.message());
    return;
  }
  {
    const std::lock_guard lock(mutex_);
    tx_bytes_ += written;
    queue_.release(in_flight_size_);
  }
  writeNext();
}

void TransportCore::writeDropped(std::uint64_t gen) {
  if (!current(gen))
    return;
  {
    const std::lock_guard lock(mutex_);
    tx_dropped_bytes_ += in_flight_size_;
    queue_.release(in_flight_size_);
  }
  writeNext();
}

void TransportCore::newGeneration() {
  const std::lock_guard lock(mutex_);
  ++generation_;
  tx_dropped_bytes_ += queue_.clear();
  write_in_flight_ = false;
  in_flight_size_ = 0;
}

void TransportCore::openNow() {
  if (!callbacks_)
    return;  // shut down
  if (state_.load() != TransportState::kClosed && state_.load() != TransportState::kFailed)
    doClose();
  newGeneration();
  setLocalPort(0);
  setState(TransportState::kOpening, "opening " + description_);
  doOpen();
}

void TransportCore::closeNow() {
  doClose();
  newGeneration();
  if (state_.load() != TransportState::kClosed)
    setState(TransportState::kClosed, "closed " + description_);
}

void TransportCore::fail(const std::string& message) {
  doClose();
  newGeneration();
  setState(TransportState::kFailed, message);
}

void TransportCore::setState(TransportState state, const std::string& message) {
  state_.store(state);
  // Copy the pointer: the callback may destroy this transport's owner (and reset callbacks_).
  const auto callbacks = callbacks_;
  if (callbacks && callbacks->on_state)
    callbacks->on_state(state, message);
}

void TransportCore::deliver(std::span<const std::uint8_t> bytes) {
  rx_bytes_.fetch_add(bytes.size());
  const auto callbacks = callbacks_;
  if (callbacks && callbacks->on_bytes)
    callbacks->on_bytes(bytes);
}

void TransportCore::refused(const std::string& peer) {
  refused_peers_.fetch_add(1);
  const auto callbacks = callbacks_;
  if (callbacks && callbacks->on_refused)
    callbacks->on_refused(peer);
}

}  // namespace detail
}  // namespace irgs::comms
