// Link end to end on the real IoThread: two Links over loopback TCP (one plays the robot by
// sending rover heartbeats and acknowledging commands) and a Link on a pty whose other end the
// test drives. Short timeouts keep the wall time small; every wait is on a condition with a
// generous deadline, never a fixed sleep.

#include "comms/link/link.hpp"

#include "comms/link/link_url.hpp"
#include "comms/mavlink/frame_encoder.hpp"
#include "comms/mavlink/messages.hpp"
#include "tests/comms/link/link_test_support.hpp"
#include "tests/comms/transport/transport_test_support.hpp"

#include <gtest/gtest.h>
#include <unistd.h>
#include <boost/asio/ip/tcp.hpp>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <filesystem>
#include <functional>
#include <future>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace irgs::comms {
namespace {

namespace mav = mavlink;
using namespace std::chrono_literals;

constexpr auto kWait = std::chrono::seconds(10);  // only reached when a test fails

// Fast timings for tests: 10 Hz heartbeats, loss after 0.4 s, reconnect within 0.2 s.
LinkConfig fastConfig() {
  LinkConfig c;
  c.tick_s = 0.01;
  c.reconnect_initial_s = 0.05;
  c.reconnect_max_s = 0.2;
  c.session.heartbeat_period_s = 0.1;
  c.session.timeout_s = 0.4;
  c.session.timesync_period_s = 0.1;
  c.session.commands.retry_s = 0.1;
  return c;
}

LinkConfig robotConfig() {
  LinkConfig c = fastConfig();
  c.session.system_id = testing::kRobotSystem;
  c.session.component_id = testing::kRobotComponent;
  c.session.heartbeat = testing::robotHeartbeat();
  c.session.timesync_period_s = 0.0;
  return c;
}

LinkUrl url(const std::string& text) {
  auto parsed = parseLinkUrl(text);
  if (!parsed.url)
    throw std::invalid_argument(parsed.error);
  return *parsed.url;
}

// Collects events (any thread) and lets the test wait for a condition on them.
class EventLog {
 public:
  LinkCallbacks callbacks() {
    LinkCallbacks cb;
    cb.on_event = [this](const LinkEvent& e) {
      const std::lock_guard lock(mutex_);
      events_.push_back(e);
      cv_.notify_all();
    };
    return cb;
  }
  std::size_t count(LinkEventKind kind) const {
    const std::lock_guard lock(mutex_);
    return countLocked(kind);
  }
  bool waitCount(LinkEventKind kind, std::size_t n) {
    std::unique_lock lock(mutex_);
    return cv_.wait_for(lock, kWait, [&] { return countLocked(kind) >= n; });
  }
  std::string dump() const {
    const std::lock_guard lock(mutex_);
    std::string out;
    for (const auto& e : events_)
      out += std::string(toString(e.kind)) + ": " + e.text + "\n";
    return out;
  }
  std::optional<LinkEvent> last(LinkEventKind kind) const {
    const std::lock_guard lock(mutex_);
    for (auto it = events_.rbegin(); it != events_.rend(); ++it)
      if (it->kind == kind)
        return *it;
    return std::nullopt;
  }

 private:
  std::size_t countLocked(LinkEventKind kind) const {
    std::size_t n = 0;
    for (const auto& e : events_)
      n += e.kind == kind ? 1u : 0u;
    return n;
  }
  mutable std::mutex mutex_;
  std::condition_variable cv_;
  std::vector<LinkEvent> events_;
};

// Polls a thread-safe predicate (Link::stats() snapshots) until it holds or kWait passes.
bool eventually(const std::function<bool()>& predicate) {
  const auto deadline = std::chrono::steady_clock::now() + kWait;
  while (std::chrono::steady_clock::now() < deadline) {
    if (predicate())
      return true;
    std::this_thread::yield();
  }
  return predicate();
}

// A robot stand-in: a TCP server Link that heartbeats as a rover and accepts every command.
class FakeRobot {
 public:
  FakeRobot(IoThread& io, std::uint16_t port, LinkConfig config = robotConfig()) {
    LinkCallbacks cb;
    cb.on_frame = [this](const mav::Frame& frame) {
      if (auto command = frame.as<mav::CommandLong>()) {
        ++commands_seen_;
        mav::CommandAck ack;
        ack.command = command->command;
        ack.result = static_cast<std::uint8_t>(mav::MavResult::kAccepted);
        ack.target_system = frame.system_id;
        ack.target_component = frame.component_id;
        if (auto* link = link_.load())
          link->send(ack);
      }
    };
    auto made = Link::create(io, url("tcp://127.0.0.1:" + std::to_string(port) + "?listen=1"),
                             std::move(config), std::move(cb));
    if (!made.link)
      throw std::runtime_error(made.error);
    owned_ = std::move(made.link);
    link_.store(owned_.get());
    owned_->open();
  }
  ~FakeRobot() {
    link_.store(nullptr);
    owned_.reset();
  }
  Link& link() { return *owned_; }
  int commandsSeen() const { return commands_seen_.load(); }

 private:
  std::atomic<Link*> link_{nullptr};
  std::unique_ptr<Link> owned_;
  std::atomic<int> commands_seen_{0};
};

// A loopback port that was free a moment ago (LinkUrl has no "any port"; the server sets
// SO_REUSEADDR, so restarting on it works as it does for a real robot).
std::uint16_t freePort() {
  boost::asio::io_context io;
  boost::asio::ip::tcp::acceptor acceptor(
      io, boost::asio::ip::tcp::endpoint(boost::asio::ip::make_address("127.0.0.1"), 0));
  return acceptor.local_endpoint().port();
}

std::uint16_t waitForPort(Link& link) {
  eventually([&] { return link.localPort() != 0; });
  return link.localPort();
}

TEST(Link, ConnectsToARobotAcknowledgesACommandAndMeasuresTheRoundTrip) {
  IoThread io;
  FakeRobot robot(io, freePort());
  const std::uint16_t port = waitForPort(robot.link());
  ASSERT_NE(port, 0);

  EventLog log;
  auto made = Link::create(io, url("tcp://127.0.0.1:" + std::to_string(port)), fastConfig(),
                           log.callbacks());
  ASSERT_TRUE(made.link) << made.error;
  Link& gcs = *made.link;
  gcs.open();
  ASSERT_TRUE(log.waitCount(LinkEventKind::kLinkUp, 1)) << log.dump();

  std::mutex m;
  std::condition_variable cv;
  std::optional<CommandResult> result;
  mav::CommandLong stop;
  stop.command = static_cast<std::uint16_t>(mav::MavCmd::kIrgsStop);
  gcs.sendCommand(stop, [&](const CommandResult& r) {
    const std::lock_guard lock(m);
    result = r;
    cv.notify_all();
  });
  {
    std::unique_lock lock(m);
    ASSERT_TRUE(cv.wait_for(lock, kWait, [&] { return result.has_value(); }));
  }
  EXPECT_EQ(result->outcome, CommandOutcome::kAccepted) << result->message;
  EXPECT_EQ(result->mav_result, static_cast<std::uint8_t>(mav::MavResult::kAccepted));
  EXPECT_GE(robot.commandsSeen(), 1);
  EXPECT_EQ(log.count(LinkEventKind::kCommandResult), 1u);

  ASSERT_TRUE(eventually([&] { return gcs.stats().rtt_s.has_value(); }));
  const auto stats = gcs.stats();
  EXPECT_EQ(stats.state, LinkState::kConnected);
  EXPECT_EQ(gcs.state(), LinkState::kConnected);
  EXPECT_LT(*stats.rtt_s, 1.0);
  EXPECT_GT(stats.rx_messages, 0u);
  EXPECT_GT(stats.tx_messages, 0u);
  EXPECT_GT(stats.rx_bytes, 0u);
  EXPECT_EQ(stats.crc_errors, 0u);
  EXPECT_EQ(stats.peer_system_id, testing::kRobotSystem);
  EXPECT_NE(gcs.description().find("127.0.0.1"), std::string::npos);
}

TEST(Link, DetectsLossWhenTheRobotGoesAwayAndReconnectsWhenItReturnsOnTheSamePort) {
  IoThread io;
  auto robot = std::make_unique<FakeRobot>(io, freePort());
  const std::uint16_t port = waitForPort(robot->link());
  ASSERT_NE(port, 0);

  EventLog log;
  auto made = Link::create(io, url("tcp://127.0.0.1:" + std::to_string(port)), fastConfig(),
                           log.callbacks());
  ASSERT_TRUE(made.link) << made.error;
  Link& gcs = *made.link;
  gcs.open();
  ASSERT_TRUE(log.waitCount(LinkEventKind::kLinkUp, 1)) << log.dump();

  robot.reset();  // robot process killed
  ASSERT_TRUE(log.waitCount(LinkEventKind::kLinkLost, 1)) << log.dump();
  EXPECT_TRUE(eventually([&] { return gcs.state() == LinkState::kLost; }));
  // While it is gone the link keeps trying (connection refused), with capped backoff.
  ASSERT_TRUE(log.waitCount(LinkEventKind::kReconnecting, 2)) << log.dump();

  robot = std::make_unique<FakeRobot>(io, port);  // restarted on the same port
  ASSERT_TRUE(log.waitCount(LinkEventKind::kLinkUp, 2)) << log.dump();
  EXPECT_TRUE(eventually([&] { return gcs.state() == LinkState::kConnected; }));
  const auto up = log.last(LinkEventKind::kLinkUp);
  ASSERT_TRUE(up);
  EXPECT_NE(up->text.find("lost"), std::string::npos);
  EXPECT_GE(gcs.stats().link_losses, 1u);
}

TEST(Link, SignedLinkConnectsWithTheSharedKeyAndRejectsAnyOther) {
  IoThread io;
  const auto key = mav::signingKeyFromPassphrase("irgs test key");
  LinkConfig robot_config = robotConfig();
  robot_config.signing_key = mav::signingKeyFromPassphrase("somebody else");
  auto impostor = std::make_unique<FakeRobot>(io, freePort(), robot_config);
  const std::uint16_t port = waitForPort(impostor->link());

  LinkConfig config = fastConfig();
  config.signing_key = key;
  config.require_signed = true;
  EventLog log;
  auto made =
      Link::create(io, url("tcp://127.0.0.1:" + std::to_string(port)), config, log.callbacks());
  ASSERT_TRUE(made.link) << made.error;
  made.link->open();
  ASSERT_TRUE(eventually([&] { return made.link->stats().other_errors >= 2; }));  // bad signature
  EXPECT_EQ(made.link->state(), LinkState::kConnecting);
  EXPECT_EQ(made.link->stats().rx_messages, 0u);

  impostor.reset();
  robot_config.signing_key = key;
  FakeRobot robot(io, port, robot_config);
  ASSERT_TRUE(log.waitCount(LinkEventKind::kLinkUp, 1)) << log.dump();
}

TEST(Link, CommandOnALinkThatWasNeverOpenedIsCancelled) {
  IoThread io;
  EventLog log;
  auto made = Link::create(io, url("tcp://127.0.0.1:9"), fastConfig(), log.callbacks());
  ASSERT_TRUE(made.link) << made.error;
  std::promise<CommandResult> done;
  made.link->sendCommand(mav::CommandLong{}, [&](const CommandResult& r) { done.set_value(r); });
  auto future = done.get_future();
  ASSERT_EQ(future.wait_for(kWait), std::future_status::ready);
  EXPECT_EQ(future.get().outcome, CommandOutcome::kCancelled);
  EXPECT_EQ(made.link->state(), LinkState::kDisconnected);
}

TEST(Link, CloseDisconnectsAndOpenConnectsAgain) {
  IoThread io;
  FakeRobot robot(io, freePort());
  const std::uint16_t port = waitForPort(robot.link());
  EventLog log;
  auto made = Link::create(io, url("tcp://127.0.0.1:" + std::to_string(port)), fastConfig(),
                           log.callbacks());
  ASSERT_TRUE(made.link) << made.error;
  made.link->open();
  ASSERT_TRUE(log.waitCount(LinkEventKind::kLinkUp, 1)) << log.dump();
  made.link->close();
  ASSERT_TRUE(log.waitCount(LinkEventKind::kClosed, 1)) << log.dump();
  EXPECT_TRUE(eventually([&] { return made.link->state() == LinkState::kDisconnected; }));
  EXPECT_EQ(log.count(LinkEventKind::kLinkLost), 0u);  // a user close is not a loss
  made.link->open();
  ASSERT_TRUE(log.waitCount(LinkEventKind::kLinkUp, 2)) << log.dump();
  EXPECT_EQ(log.count(LinkEventKind::kReconnecting), 0u) << log.dump();
}

TEST(Link, ReportsBadUrlOptionsAndConfigurationAsErrors) {
  IoThread io;
  auto bad_option = Link::create(io, url("serial:///dev/ttyUSB0?flow=sideways"));
  EXPECT_FALSE(bad_option.link);
  EXPECT_FALSE(bad_option.error.empty());
  LinkConfig config;
  config.session.timeout_s = 0.0;
  auto bad_config = Link::create(io, url("tcp://127.0.0.1:5760"), config);
  EXPECT_FALSE(bad_config.link);
  EXPECT_NE(bad_config.error.find("timeout_s"), std::string::npos);
}

// Serial over a pty: the test writes one robot heartbeat; the link connects, declares the link
// lost after the timeout although the device stays open, reopens the device and connects again
// when heartbeats resume.
TEST(Link, SerialLinkDetectsSilenceAndRecoversWhenHeartbeatsResume) {
  testing::PtyPair pty;
  IoThread io;
  EventLog log;
  auto made = Link::create(io, url("serial://" + pty.slavePath() + "?baud=115200&exclusive=0"),
                           fastConfig(), log.callbacks());
  ASSERT_TRUE(made.link) << made.error;
  Link& gcs = *made.link;
  gcs.open();

  mav::FrameEncoder robot(testing::kRobotSystem, testing::kRobotComponent);
  auto heartbeatBytes = [&] {
    const auto frame = robot.encode(testing::robotHeartbeat());
    return std::vector<std::uint8_t>(frame.view().begin(), frame.view().end());
  };
  // Our heartbeat arriving on the master side proves the device is open.
  std::vector<std::uint8_t> first_bytes;
  ASSERT_TRUE(pty.readExactly(1, first_bytes));
  ASSERT_TRUE(pty.writeAll(heartbeatBytes()));
  ASSERT_TRUE(log.waitCount(LinkEventKind::kLinkUp, 1)) << log.dump();
  ASSERT_TRUE(log.waitCount(LinkEventKind::kLinkLost, 1)) << log.dump();
  // On the link's own clock: not before the timeout (0.4 s), and promptly after it (the
  // upper bound leaves room for a loaded machine delaying ticks).
  const double silent_s =
      log.last(LinkEventKind::kLinkLost)->time_s - log.last(LinkEventKind::kLinkUp)->time_s;
  EXPECT_GT(silent_s, 0.4);
  EXPECT_LT(silent_s, 0.4 + 1.0);
  ASSERT_TRUE(log.waitCount(LinkEventKind::kReconnecting, 1)) << log.dump();

  // Heartbeats resume (written repeatedly: one may land while the device is being reopened).
  const auto deadline = std::chrono::steady_clock::now() + kWait;
  while (log.count(LinkEventKind::kLinkUp) < 2 && std::chrono::steady_clock::now() < deadline) {
    ASSERT_TRUE(pty.writeAll(heartbeatBytes()));
    std::vector<std::uint8_t> echo;
    pty.readExactly(1, echo);  // paced by the link's own traffic (10 Hz heartbeats)
  }
  EXPECT_GE(log.count(LinkEventKind::kLinkUp), 2u) << log.dump();
}

// USB replug / Bluetooth drop: the device node vanishes and a new one appears under the same
// name (here a symlink, as udev rules and `irgs-robot --link` provide).
TEST(Link, SerialLinkReconnectsWhenTheDeviceNodeDisappearsAndComesBack) {
  const std::filesystem::path node = std::filesystem::temp_directory_path() /
                                     ("irgs-link-test-" + std::to_string(::getpid()) + "-tty");
  std::filesystem::remove(node);
  auto first = std::make_unique<testing::PtyPair>();
  std::optional<testing::PtyPair> second;
  std::filesystem::create_symlink(first->slavePath(), node);

  IoThread io;
  EventLog log;
  auto made = Link::create(io, url("serial://" + node.string() + "?baud=57600&exclusive=0"),
                           fastConfig(), log.callbacks());
  ASSERT_TRUE(made.link) << made.error;
  made.link->open();

  mav::FrameEncoder robot(testing::kRobotSystem, testing::kRobotComponent);
  const auto encoded = robot.encode(testing::robotHeartbeat());
  const std::vector<std::uint8_t> heartbeat(encoded.view().begin(), encoded.view().end());
  std::vector<std::uint8_t> bytes;
  ASSERT_TRUE(first->readExactly(1, bytes));
  ASSERT_TRUE(first->writeAll(heartbeat));
  ASSERT_TRUE(log.waitCount(LinkEventKind::kLinkUp, 1)) << log.dump();

  first->closeMaster();  // the device goes away ...
  std::filesystem::remove(node);
  ASSERT_TRUE(log.waitCount(LinkEventKind::kLinkLost, 1)) << log.dump();
  ASSERT_TRUE(log.waitCount(LinkEventKind::kReconnecting, 2)) << log.dump();  // node missing
  EXPECT_EQ(made.link->state(), LinkState::kLost);

  second.emplace();  // ... and comes back under the same name
  std::filesystem::create_symlink(second->slavePath(), node);
  ASSERT_TRUE(second->readExactly(1, bytes)) << log.dump();  // reopened: our heartbeat arrives
  const auto deadline = std::chrono::steady_clock::now() + kWait;
  while (log.count(LinkEventKind::kLinkUp) < 2 && std::chrono::steady_clock::now() < deadline) {
    ASSERT_TRUE(second->writeAll(heartbeat));
    second->readExactly(1, bytes);  // paced by the link's own traffic
  }
  EXPECT_GE(log.count(LinkEventKind::kLinkUp), 2u) << log.dump();
  made.link.reset();
  std::filesystem::remove(node);
}

}  // namespace
}  // namespace irgs::comms
