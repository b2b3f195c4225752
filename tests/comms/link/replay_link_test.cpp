// A Link on a ReplayTransport (issue 6 item 3): recorded bytes pushed into a ReplayFeed reach the
// same decoder and link session a live transport feeds, in order, across arbitrary chunk
// boundaries; the frame tap sees every received chunk and every sent frame (issue 6 item 2).

#include "comms/link/link.hpp"

#include "comms/mavlink/frame_encoder.hpp"
#include "comms/mavlink/messages.hpp"
#include "comms/transport/replay_transport.hpp"
#include "tests/comms/link/link_test_support.hpp"

#include <gtest/gtest.h>
#include <boost/asio/post.hpp>

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <functional>
#include <future>
#include <mutex>
#include <thread>
#include <vector>

namespace irgs::comms {
namespace {

namespace mav = mavlink;
constexpr auto kWait = std::chrono::seconds(10);  // only reached when a test fails

struct Seen {
  std::mutex mutex;
  std::condition_variable changed;
  std::vector<std::uint8_t> frame_sequences;
  std::vector<std::uint8_t> tapped_rx;
  std::size_t tapped_tx_frames = 0;
  bool tapped_after_close = false;

  bool waitFor(const std::function<bool()>& done) {
    std::unique_lock lock(mutex);
    return changed.wait_for(lock, kWait, done);
  }
};

LinkConfig replayConfig(const std::shared_ptr<ReplayFeed>& feed, Seen& seen) {
  LinkConfig config;
  config.tick_s = 0.01;
  config.session.heartbeat_period_s = 0.05;
  config.make_transport = replayTransportMaker(feed, "replay test");
  config.tap = [&seen](TapDirection direction, std::chrono::steady_clock::time_point,
                       std::span<const std::uint8_t> bytes) {
    const std::lock_guard lock(seen.mutex);
    if (direction == TapDirection::kReceived)
      seen.tapped_rx.insert(seen.tapped_rx.end(), bytes.begin(), bytes.end());
    else
      ++seen.tapped_tx_frames;
    seen.changed.notify_all();
  };
  return config;
}

LinkCallbacks frameCollector(Seen& seen) {
  LinkCallbacks callbacks;
  callbacks.on_frame = [&seen](const mav::Frame& frame) {
    const std::lock_guard lock(seen.mutex);
    seen.frame_sequences.push_back(frame.sequence);
    seen.changed.notify_all();
  };
  return callbacks;
}

// Ten robot heartbeats as one byte stream (sequence 0..9).
std::vector<std::uint8_t> heartbeatStream() {
  mav::FrameEncoder encoder(testing::kRobotSystem, testing::kRobotComponent);
  std::vector<std::uint8_t> stream;
  for (int i = 0; i < 10; ++i) {
    const auto frame = encoder.encode(testing::robotHeartbeat());
    stream.insert(stream.end(), frame.view().begin(), frame.view().end());
  }
  return stream;
}

// A link on `feed`, opened, that has taken in heartbeatStream() (frames 0..9 in `seen`).
LinkResult linkThatHeardHeartbeats(IoThread& io, const std::shared_ptr<ReplayFeed>& feed,
                                   Seen& seen) {
  LinkResult made = Link::create(io, LinkUrl{}, replayConfig(feed, seen), frameCollector(seen));
  if (!made.link)
    return made;
  made.link->open();
  feed->push(heartbeatStream());
  if (!seen.waitFor([&] { return seen.frame_sequences.size() == 10; }))
    made.link.reset();
  return made;
}

TEST(ReplayLink, PushedChunksAreDecodedInOrderAcrossChunkBoundariesAndTapped) {
  IoThread io;
  auto feed = std::make_shared<ReplayFeed>();
  Seen seen;
  LinkResult made = Link::create(io, LinkUrl{}, replayConfig(feed, seen), frameCollector(seen));
  ASSERT_TRUE(made.link) << made.error;
  made.link->open();
  const std::vector<std::uint8_t> stream = heartbeatStream();
  // Chunks of 7 bytes: every frame is split, as a serial read splits them.
  for (std::size_t i = 0; i < stream.size(); i += 7)
    feed->push(std::vector<std::uint8_t>(
        stream.begin() + static_cast<std::ptrdiff_t>(i),
        stream.begin() + static_cast<std::ptrdiff_t>(std::min(stream.size(), i + 7))));
  ASSERT_TRUE(seen.waitFor([&] { return seen.frame_sequences.size() == 10; }));
  for (std::uint8_t i = 0; i < 10; ++i)
    EXPECT_EQ(seen.frame_sequences[i], i);
  EXPECT_TRUE(seen.waitFor([&] { return made.link->state() == LinkState::kConnected; }));
  // Our own heartbeats went to the (discarding) replay transport and through the tap.
  EXPECT_TRUE(seen.waitFor([&] { return seen.tapped_tx_frames >= 1; }));
  {
    const std::lock_guard lock(seen.mutex);
    EXPECT_EQ(seen.tapped_rx, stream);
  }
  EXPECT_EQ(feed->droppedBytes(), 0u);
  EXPECT_EQ(feed->deliveredBytes(), stream.size());
  EXPECT_EQ(made.link->stats().crc_errors, 0u);
}

TEST(ReplayLink, BytesPushedWithNoTransportAttachedAreDroppedAndCounted) {
  auto feed = std::make_shared<ReplayFeed>();
  feed->push({1, 2, 3});
  EXPECT_FALSE(feed->attached());
  EXPECT_EQ(feed->droppedBytes(), 3u);
  EXPECT_EQ(feed->pushedBytes(), 3u);

  IoThread io;
  Seen seen;
  {
    LinkResult made = Link::create(io, LinkUrl{}, replayConfig(feed, seen), frameCollector(seen));
    ASSERT_TRUE(made.link);
    EXPECT_TRUE(feed->attached());
  }
  EXPECT_FALSE(feed->attached());  // the link (and its transport) is gone
  feed->push({4, 5});
  EXPECT_EQ(feed->droppedBytes(), 5u);
}

TEST(ReplayLink, ARebuiltLinkTakesOverTheFeed) {
  IoThread io;
  auto feed = std::make_shared<ReplayFeed>();
  Seen first_seen, second_seen;
  LinkResult first =
      Link::create(io, LinkUrl{}, replayConfig(feed, first_seen), frameCollector(first_seen));
  ASSERT_TRUE(first.link);
  first.link->open();
  const std::vector<std::uint8_t> stream = heartbeatStream();
  feed->push(stream);
  ASSERT_TRUE(first_seen.waitFor([&] { return first_seen.frame_sequences.size() == 10; }));

  first.link.reset();
  LinkResult second =
      Link::create(io, LinkUrl{}, replayConfig(feed, second_seen), frameCollector(second_seen));
  ASSERT_TRUE(second.link);
  second.link->open();
  feed->push(stream);
  ASSERT_TRUE(second_seen.waitFor([&] { return second_seen.frame_sequences.size() == 10; }));
  EXPECT_EQ(first_seen.frame_sequences.size(), 10u);
}

TEST(ReplayLink, BytesReadAfterCloseAreNeitherTappedNorDecoded) {
  // close() closes the transport on a handler of its own: a read completing in between used to be
  // tapped and decoded after the owner had taken its last data (LinkedRobot::finish), so a
  // recording held a sample the live map never had. On the io thread: close, then a chunk that
  // the still-open transport delivers before its close handler runs.
  IoThread io;
  auto feed = std::make_shared<ReplayFeed>();
  Seen seen;
  LinkResult made = linkThatHeardHeartbeats(io, feed, seen);
  ASSERT_TRUE(made.link) << "no link, or it did not take in the heartbeats: " << made.error;
  const std::vector<std::uint8_t> stream = heartbeatStream();

  std::promise<void> pushed;
  boost::asio::post(io.context(), [&] {
    made.link->close();
    feed->push(stream);
    pushed.set_value();
  });
  pushed.get_future().wait();
  // The chunk's own handler (posted by push) is in the queue: poll for it (nothing notifies).
  const auto deadline = std::chrono::steady_clock::now() + kWait;
  while (feed->deliveredBytes() + feed->droppedBytes() < 2 * stream.size() &&
         std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  std::promise<void> drained;  // every handler posted so far has run
  boost::asio::post(io.context(), [&] { drained.set_value(); });
  drained.get_future().wait();
  EXPECT_EQ(feed->deliveredBytes(), 2 * stream.size()) << "the chunk did reach the link";
  const std::lock_guard lock(seen.mutex);
  EXPECT_EQ(seen.frame_sequences.size(), 10u);
  EXPECT_EQ(seen.tapped_rx.size(), stream.size());  // the first stream only
}

TEST(ReplayLink, AReplayTransportMakerNeedsAFeed) {
  EXPECT_THROW(replayTransportMaker(nullptr, "x"), std::invalid_argument);
}

}  // namespace
}  // namespace irgs::comms
