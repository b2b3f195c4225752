#pragma once
// Shared machinery of the Asio transports (internal header): state, statistics, the bounded TX
// queue with one write in flight, callback dispatch, and session generations so completions of
// a closed session are ignored. Concrete cores implement doOpen/doClose/doWrite; the public
// object is `AsioTransport`, a thin owner that closes the core synchronously on destruction.

#include "comms/transport/io_thread.hpp"
#include "comms/transport/transport.hpp"
#include "comms/transport/tx_queue.hpp"

#include <boost/system/error_code.hpp>

#include <atomic>
#include <memory>
#include <mutex>
#include <string>

namespace irgs::comms::detail {

class TransportCore : public std::enable_shared_from_this<TransportCore> {
 public:
  TransportCore(IoThread& io, std::size_t tx_capacity_bytes, std::string description,
                TransportCallbacks callbacks);
  virtual ~TransportCore() = default;
  TransportCore(const TransportCore&) = delete;
  TransportCore& operator=(const TransportCore&) = delete;

  // Any thread.
  void requestOpen();
  void requestClose();
  bool send(std::span<const std::uint8_t> bytes);
  TransportState state() const { return state_.load(); }
  TransportStats stats() const;
  std::uint16_t localPort() const { return local_port_.load(); }
  const std::string& description() const { return description_; }
  // Closes and forgets the callbacks; when it returns no callback runs any more.
  void shutdown();

 protected:
  // ---- io thread only ----
  // Start opening (the state is already kOpening and generation() is the new session). Must end
  // in setState(kOpen, ...) or fail(...), possibly asynchronously.
  virtual void doOpen() = 0;
  // Release OS resources and cancel pending operations. No callbacks from here.
  virtual void doClose() = 0;
  // Start one asynchronous write of `chunk`; on completion call writeDone(gen, ec, n) (or
  // writeDropped for datagrams that could not be sent without the link being broken).
  virtual void doWrite(std::uint64_t gen, TxQueue::Chunk chunk) = 0;
  // Extra condition for send() besides state == open (UDP listener: a peer is known). Any thread.
  virtual bool readyToSend() const { return true; }

  void setState(TransportState state, const std::string& message);
  // doClose(), discard the queue, state -> failed with `message`.
  void fail(const std::string& message);
  void deliver(std::span<const std::uint8_t> bytes);
  void writeDone(std::uint64_t gen, const boost::system::error_code& ec, std::size_t written);
  void writeDropped(std::uint64_t gen);
  // A listener turned `peer` away: counts it and tells on_refused.
  void refused(const std::string& peer);
  // Ends the current session's I/O: bumps the generation, discards queued bytes. Used by close,
  // fail and a TCP server whose client changes.
  void newGeneration();
  std::uint64_t generation() const { return generation_; }
  bool current(std::uint64_t gen) const { return gen == generation_; }
  void setLocalPort(std::uint16_t port) { local_port_.store(port); }
  boost::asio::io_context& io() { return io_.context(); }

  template <typename Derived>
  std::shared_ptr<Derived> self() {
    return std::static_pointer_cast<Derived>(shared_from_this());
  }

 private:
  void openNow();
  void closeNow();
  void kickWrite(std::uint64_t gen);
  void writeNext();  // io thread, mutex_ not held

  IoThread& io_;
  const std::string description_;
  std::shared_ptr<const TransportCallbacks> callbacks_;  // io thread only

  std::atomic<TransportState> state_{TransportState::kClosed};
  std::atomic<std::uint16_t> local_port_{0};
  std::atomic<std::uint64_t> rx_bytes_{0};
  std::atomic<std::uint64_t> refused_peers_{0};

  mutable std::mutex mutex_;  // guards everything below
  TxQueue queue_;
  bool write_in_flight_ = false;
  std::size_t in_flight_size_ = 0;
  std::uint64_t generation_ = 0;  // written on the io thread under mutex_
  std::uint64_t tx_bytes_ = 0;
  std::uint64_t tx_dropped_bytes_ = 0;
};

// The public Transport over a core.
class AsioTransport final : public Transport {
 public:
  explicit AsioTransport(std::shared_ptr<TransportCore> core) : core_(std::move(core)) {}
  ~AsioTransport() override { core_->shutdown(); }

  void open() override { core_->requestOpen(); }
  void close() override { core_->requestClose(); }
  bool send(std::span<const std::uint8_t> bytes) override { return core_->send(bytes); }
  TransportState state() const override { return core_->state(); }
  TransportStats stats() const override { return core_->stats(); }
  std::string description() const override { return core_->description(); }
  std::uint16_t localPort() const override { return core_->localPort(); }

 private:
  std::shared_ptr<TransportCore> core_;
};

}  // namespace irgs::comms::detail
