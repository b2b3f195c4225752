#include "comms/transport/replay_transport.hpp"

#include <boost/asio/post.hpp>

#include <deque>
#include <stdexcept>
#include <utility>

namespace irgs::comms {

namespace detail {

// The io-thread side shared by the public transport, the feed and posted handlers. A recursive
// mutex guards `alive_` and the callbacks: the transport's destructor may run inside one of its
// own callbacks (same thread, lock held), and from another thread it waits for a running
// callback to return, after which none starts.
class ReplayCore : public std::enable_shared_from_this<ReplayCore> {
 public:
  ReplayCore(IoThread& io, std::string description, TransportCallbacks callbacks,
             std::shared_ptr<ReplayFeed> feed)
      : io_(io),
        description_(std::move(description)),
        callbacks_(std::move(callbacks)),
        feed_(std::move(feed)) {}

  // Chunks pushed after open() but before the open state was reported (the feed and the link
  // post to the io thread independently) wait for it instead of being dropped.
  void requestOpen() {
    open_requested_.store(true);
    post([](ReplayCore& core) { core.setState(TransportState::kOpen, core.description_); });
  }
  void requestClose() {
    open_requested_.store(false);
    post([](ReplayCore& core) { core.setState(TransportState::kClosed, {}); });
  }
  bool send(std::span<const std::uint8_t> bytes) {
    if (state_.load() != TransportState::kOpen) {
      tx_dropped_bytes_.fetch_add(bytes.size());
      return false;
    }
    tx_bytes_.fetch_add(bytes.size());
    return true;
  }
  void deliverLater(std::vector<std::uint8_t> bytes) {
    boost::asio::post(io_.context(), [self = shared_from_this(), data = std::move(bytes)] {
      self->deliver(data);
    });
  }
  void shutdown() {
    const std::lock_guard lock(mutex_);
    alive_ = false;
    state_.store(TransportState::kClosed);
  }

  TransportState state() const { return state_.load(); }
  TransportStats stats() const {
    TransportStats s;
    s.rx_bytes = rx_bytes_.load();
    s.tx_bytes = tx_bytes_.load();
    s.tx_dropped_bytes = tx_dropped_bytes_.load();
    return s;
  }
  const std::string& description() const { return description_; }

 private:
  template <class F>
  void post(F f) {
    boost::asio::post(io_.context(), [self = shared_from_this(), f] { f(*self); });
  }
  void setState(TransportState state, const std::string& message) {
    const std::lock_guard lock(mutex_);
    if (!alive_)
      return;
    state_.store(state);
    if (callbacks_.on_state)
      callbacks_.on_state(state, message);
    if (state == TransportState::kOpen) {
      std::deque<std::vector<std::uint8_t>> waiting = std::move(waiting_);
      waiting_.clear();
      for (const auto& bytes : waiting)
        deliver(bytes);
    } else {
      for (const auto& bytes : waiting_)
        feed_->dropped_bytes_.fetch_add(bytes.size());
      waiting_.clear();
    }
  }
  void deliver(const std::vector<std::uint8_t>& bytes) {
    const std::lock_guard lock(mutex_);
    if (alive_ && state_.load() != TransportState::kOpen && open_requested_.load()) {
      waiting_.push_back(bytes);
      return;
    }
    if (!alive_ || state_.load() != TransportState::kOpen) {
      feed_->dropped_bytes_.fetch_add(bytes.size());
      return;
    }
    // Counted before the hand-over: whoever sees the bytes' effects (a decoded frame on another
    // thread) must also see them counted.
    rx_bytes_.fetch_add(bytes.size());
    feed_->delivered_bytes_.fetch_add(bytes.size());
    if (callbacks_.on_bytes)
      callbacks_.on_bytes(bytes);
  }

  IoThread& io_;
  const std::string description_;
  const TransportCallbacks callbacks_;
  const std::shared_ptr<ReplayFeed> feed_;
  std::recursive_mutex mutex_;
  bool alive_ = true;
  std::atomic<bool> open_requested_{false};
  std::deque<std::vector<std::uint8_t>> waiting_;  // io thread, under mutex_
  std::atomic<TransportState> state_{TransportState::kClosed};
  std::atomic<std::uint64_t> rx_bytes_{0};
  std::atomic<std::uint64_t> tx_bytes_{0};
  std::atomic<std::uint64_t> tx_dropped_bytes_{0};
};

namespace {

class ReplayTransport final : public Transport {
 public:
  explicit ReplayTransport(std::shared_ptr<ReplayCore> core) : core_(std::move(core)) {}
  ~ReplayTransport() override { core_->shutdown(); }

  void open() override { core_->requestOpen(); }
  void close() override { core_->requestClose(); }
  bool send(std::span<const std::uint8_t> bytes) override { return core_->send(bytes); }
  TransportState state() const override { return core_->state(); }
  TransportStats stats() const override { return core_->stats(); }
  std::string description() const override { return core_->description(); }
  std::uint16_t localPort() const override { return 0; }

 private:
  std::shared_ptr<ReplayCore> core_;
};

}  // namespace
}  // namespace detail

void ReplayFeed::push(std::vector<std::uint8_t> bytes) {
  pushed_bytes_.fetch_add(bytes.size());
  std::shared_ptr<detail::ReplayCore> core;
  {
    const std::lock_guard lock(mutex_);
    core = target_.lock();
  }
  if (!core) {  // open/closed is decided on the io thread, in order with open() and close()
    dropped_bytes_.fetch_add(bytes.size());
    return;
  }
  core->deliverLater(std::move(bytes));
}

bool ReplayFeed::attached() const {
  const std::lock_guard lock(mutex_);
  return !target_.expired();
}

void ReplayFeed::attach(const std::shared_ptr<detail::ReplayCore>& core) {
  const std::lock_guard lock(mutex_);
  target_ = core;
}

std::function<TransportResult(IoThread&, TransportCallbacks)> replayTransportMaker(
    std::shared_ptr<ReplayFeed> feed, std::string description) {
  if (!feed)
    throw std::invalid_argument("replayTransportMaker: null feed");
  return [feed = std::move(feed), description = std::move(description)](
             IoThread& io, TransportCallbacks callbacks) -> TransportResult {
    auto core = std::make_shared<detail::ReplayCore>(io, description, std::move(callbacks), feed);
    feed->attach(core);
    return {std::make_unique<detail::ReplayTransport>(core), {}};
  };
}

}  // namespace irgs::comms
