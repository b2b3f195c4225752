// The replay player (issue 6 item 3): feeds a recording's received chunks with their recorded
// timing scaled by the speed, clamps the speed to x0.25..x16, steps one chunk, and seeks
// backwards by asking for a fresh robot and re-feeding from the start.

#include "app/recording/replay_player.hpp"
#include "comms/transport/replay_transport.hpp"
#include "tests/app/recording/recording_test_support.hpp"

#include <gtest/gtest.h>

#include <QSignalSpy>

#include <chrono>
#include <cmath>
#include <condition_variable>
#include <mutex>

namespace irgs::recording {
namespace {

// A transport from the feed's maker on a real io thread, collecting what it receives.
struct Sink {
  comms::IoThread io;
  std::mutex mutex;
  std::condition_variable changed;
  std::vector<std::uint8_t> received;
  std::unique_ptr<comms::Transport> transport;

  explicit Sink(const std::shared_ptr<comms::ReplayFeed>& feed) {
    comms::TransportCallbacks callbacks;
    callbacks.on_bytes = [this](std::span<const std::uint8_t> bytes) {
      const std::lock_guard lock(mutex);
      received.insert(received.end(), bytes.begin(), bytes.end());
      changed.notify_all();
    };
    transport = comms::replayTransportMaker(feed, "test")(io, callbacks).transport;
    transport->open();
  }
  ~Sink() { transport.reset(); }
  std::vector<std::uint8_t> waitFor(std::size_t count) {
    std::unique_lock lock(mutex);
    changed.wait_for(lock, std::chrono::seconds(10), [&] { return received.size() >= count; });
    return received;
  }
};

// Received chunks {i} at t = i * 0.1 s (i = 0..9), one sent frame, an event at 1.5 s.
std::shared_ptr<const Recording> tenChunks() {
  auto r = std::make_shared<Recording>();
  for (std::uint8_t i = 0; i < 10; ++i)
    r->frames.push_back({0.1 * i, 0, {i}});
  r->frames.push_back({0.35, 1, {0xee}});
  r->events.push_back({1.5, "info", "end"});
  return r;
}

class ReplayPlayerTest : public ::testing::Test {
 protected:
  void SetUp() override { testing::ensureCoreApplication(); }
  std::shared_ptr<comms::ReplayFeed> feed_ = std::make_shared<comms::ReplayFeed>();
};

TEST_F(ReplayPlayerTest, FeedsReceivedChunksByRecordedTimeTimesSpeed) {
  Sink sink(feed_);
  ReplayPlayer player(tenChunks(), feed_);
  EXPECT_DOUBLE_EQ(player.duration_s(), 1.5);
  EXPECT_EQ(player.chunkCount(), 10u);
  player.setSpeed(2.0);
  player.play();
  player.advance(0.1);  // 0.2 s of recording: chunks at 0, 0.1, 0.2
  EXPECT_EQ(player.chunksFed(), 3u);
  EXPECT_DOUBLE_EQ(player.position_s(), 0.2);
  player.pause();
  player.advance(1.0);  // paused: nothing
  EXPECT_EQ(player.chunksFed(), 3u);
  EXPECT_EQ(sink.waitFor(3), (std::vector<std::uint8_t>{0, 1, 2}));  // never the sent frame
}

TEST_F(ReplayPlayerTest, PlaysToTheEndOnceAndReportsIt) {
  Sink sink(feed_);
  ReplayPlayer player(tenChunks(), feed_);
  QSignalSpy finished(&player, &ReplayPlayer::finished);
  player.play();
  for (int i = 0; i < 20; ++i)
    player.advance(0.1);
  EXPECT_EQ(finished.count(), 1);
  EXPECT_FALSE(player.playing());
  EXPECT_TRUE(player.atEnd());
  EXPECT_EQ(sink.waitFor(10).size(), 10u);
  player.play();  // at the end: stays paused
  EXPECT_FALSE(player.playing());
}

TEST_F(ReplayPlayerTest, ClampsTheSpeedToAQuarterAndSixteen) {
  ReplayPlayer player(tenChunks(), feed_);
  player.setSpeed(100.0);
  EXPECT_EQ(player.speed(), ReplayPlayer::kMaxSpeed);
  player.setSpeed(0.01);
  EXPECT_EQ(player.speed(), ReplayPlayer::kMinSpeed);
  player.setSpeed(std::nan(""));
  EXPECT_EQ(player.speed(), ReplayPlayer::kMinSpeed);
}

TEST_F(ReplayPlayerTest, StepFeedsExactlyTheNextChunkAndPauses) {
  Sink sink(feed_);
  ReplayPlayer player(tenChunks(), feed_);
  player.play();
  player.step();
  EXPECT_FALSE(player.playing());
  EXPECT_EQ(player.chunksFed(), 1u);
  player.step();
  EXPECT_EQ(player.chunksFed(), 2u);
  EXPECT_DOUBLE_EQ(player.position_s(), 0.1);
  EXPECT_EQ(sink.waitFor(2), (std::vector<std::uint8_t>{0, 1}));
}

TEST_F(ReplayPlayerTest, SeekingBackRequestsARestartAndRefeedsFromTheStart) {
  ReplayPlayer player(tenChunks(), feed_);
  QSignalSpy restart(&player, &ReplayPlayer::restartRequested);
  player.seek(0.55);  // forward: no restart
  EXPECT_EQ(restart.count(), 0);
  EXPECT_EQ(player.chunksFed(), 6u);
  player.play();
  player.seek(0.25);  // backwards
  EXPECT_EQ(restart.count(), 1);
  EXPECT_EQ(player.chunksFed(), 3u);
  EXPECT_DOUBLE_EQ(player.position_s(), 0.25);
  EXPECT_TRUE(player.playing());        // resumes as it was
  EXPECT_EQ(feed_->pushedBytes(), 9u);  // 6 then 3 again
  player.seek(-5.0);                    // clamped to 0
  EXPECT_DOUBLE_EQ(player.position_s(), 0.0);
  EXPECT_EQ(restart.count(), 2);
}

TEST_F(ReplayPlayerTest, ALongSeekCatchesUpInSlicesOfTwoSeconds) {
  auto r = std::make_shared<Recording>();
  for (int i = 0; i <= 100; ++i)
    r->frames.push_back({0.1 * i, 0, {1}});
  ReplayPlayer player(r, feed_);
  player.seek(9.0);
  EXPECT_TRUE(player.seeking());
  EXPECT_NEAR(player.position_s(), ReplayPlayer::kCatchUp_s, 1e-12);
  for (int i = 0; i < 10 && player.seeking(); ++i)
    player.advance(0.0);
  EXPECT_FALSE(player.seeking());
  EXPECT_DOUBLE_EQ(player.position_s(), 9.0);
  EXPECT_EQ(player.chunksFed(), 91u);
}

TEST_F(ReplayPlayerTest, RefusesANullRecording) {
  EXPECT_THROW(ReplayPlayer(nullptr, feed_), std::invalid_argument);
}

}  // namespace
}  // namespace irgs::recording
