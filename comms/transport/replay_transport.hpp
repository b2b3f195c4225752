#pragma once
// A Transport fed from memory: replay of a recorded session through the same decoder, link
// session and LinkedRobot a live link uses (docs/gui.md, "Recording and replay"). The producer
// (the replay player) pushes the recorded received chunks into a ReplayFeed with the timing it
// chooses; the feed hands each chunk, in order, to the ReplayTransport currently attached, on that
// transport's io thread, exactly as a serial read would. What the link sends (heartbeats,
// MANUAL_CONTROL, commands) is accepted and discarded: a recording cannot answer.
//
// Use: LinkConfig::make_transport = replayTransportMaker(feed, "replay session.irgsrec"). Every
// transport that maker builds becomes the feed's target, replacing the previous one (a robot
// rebuilt for a seek backwards gets the chunks from then on).
//
// Threading: ReplayFeed may be used from any thread. The transport follows the Transport
// contract (comms/transport/transport.hpp): callbacks on the io thread, none after the
// destructor returned (also when it runs inside one of them).

#include "comms/transport/io_thread.hpp"
#include "comms/transport/transport.hpp"
#include "comms/transport/transport_factory.hpp"

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace irgs::comms {

namespace detail {
class ReplayCore;
}

class ReplayFeed {
 public:
  // Queues `bytes` for the attached transport. Bytes that arrive while no transport is attached,
  // or while it is not open, are dropped and counted (as a closed port would lose them).
  void push(std::vector<std::uint8_t> bytes);
  std::uint64_t droppedBytes() const { return dropped_bytes_.load(); }
  std::uint64_t pushedBytes() const { return pushed_bytes_.load(); }
  // Bytes handed to a transport's on_bytes so far: pushed = delivered + dropped + in flight.
  std::uint64_t deliveredBytes() const { return delivered_bytes_.load(); }
  // True while a transport built from this feed exists.
  bool attached() const;

 private:
  friend class detail::ReplayCore;
  friend std::function<TransportResult(IoThread&, TransportCallbacks)> replayTransportMaker(
      std::shared_ptr<ReplayFeed> feed, std::string description);
  void attach(const std::shared_ptr<detail::ReplayCore>& core);

  mutable std::mutex mutex_;
  std::weak_ptr<detail::ReplayCore> target_;
  std::atomic<std::uint64_t> dropped_bytes_{0};
  std::atomic<std::uint64_t> pushed_bytes_{0};
  std::atomic<std::uint64_t> delivered_bytes_{0};
};

// A maker for LinkConfig::make_transport. `description` is what Link::description() reports.
// Throws std::invalid_argument for a null feed.
std::function<TransportResult(IoThread&, TransportCallbacks)> replayTransportMaker(
    std::shared_ptr<ReplayFeed> feed, std::string description);

}  // namespace irgs::comms
