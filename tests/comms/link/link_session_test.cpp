// LinkSession with a fake clock: every time is an argument, so these tests are exact.

#include "comms/link/link_session.hpp"

#include "tests/comms/link/link_test_support.hpp"

#include <gtest/gtest.h>

#include <optional>
#include <string>
#include <vector>

namespace irgs::comms {
namespace {

namespace mav = mavlink;
using testing::eventsOf;
using testing::frameOf;
using testing::messagesOf;
using testing::robotHeartbeat;

constexpr double kTick = 0.05;

// A started session with an open transport, its opening output discarded.
LinkSession openSession(LinkSessionConfig config = {}) {
  LinkSession s(config);
  s.start(0.0);
  s.onTransportOpen(0.0, "test transport");
  s.takeOutput();
  return s;
}

// Ticks from `from` (exclusive) to `to` (inclusive) and returns everything produced.
SessionOutput run(LinkSession& s, double from, double to) {
  SessionOutput all;
  for (int i = 1; from + i * kTick <= to + 1e-9; ++i) {
    s.tick(from + i * kTick);
    auto out = s.takeOutput();
    for (auto& m : out.messages)
      all.messages.push_back(m);
    for (auto& e : out.events)
      all.events.push_back(e);
    for (auto& c : out.completed)
      all.completed.push_back(std::move(c));
  }
  return all;
}

mav::CommandLong moveCommand() {
  mav::CommandLong c;
  c.command = static_cast<std::uint16_t>(mav::MavCmd::kIrgsMoveDistance);
  c.param1 = 0.5f;
  return c;
}

TEST(LinkSession, SendsAGcsHeartbeatAtOnceAndThenOncePerSecond) {
  LinkSession s;
  s.start(0.0);
  s.onTransportOpen(0.0, "test");
  auto first = s.takeOutput();
  const auto hb = messagesOf<mav::Heartbeat>(first);
  ASSERT_EQ(hb.size(), 1u);
  EXPECT_EQ(hb[0].type, static_cast<std::uint8_t>(mav::MavType::kGcs));
  EXPECT_EQ(hb[0].autopilot, static_cast<std::uint8_t>(mav::MavAutopilot::kInvalid));
  EXPECT_EQ(messagesOf<mav::Heartbeat>(run(s, 0.0, 3.0)).size(), 3u);  // t = 1, 2, 3
}

TEST(LinkSession, SendsNoHeartbeatWhileTheTransportIsDown) {
  LinkSession s = openSession();
  s.onTransportDown(0.1, "device gone");
  EXPECT_TRUE(messagesOf<mav::Heartbeat>(run(s, 0.1, 3.0)).empty());
}

TEST(LinkSession, FirstRobotHeartbeatConnects) {
  LinkSession s = openSession();
  EXPECT_EQ(s.state(), LinkState::kConnecting);
  s.onFrame(frameOf(robotHeartbeat()), 0.3);
  EXPECT_EQ(s.state(), LinkState::kConnected);
  const auto up = eventsOf(s.takeOutput(), LinkEventKind::kLinkUp);
  ASSERT_EQ(up.size(), 1u);
  EXPECT_NE(up[0].text.find("system 1"), std::string::npos);
  EXPECT_EQ(s.stats(0.3).peer_system_id, 1);
}

TEST(LinkSession, HeartbeatsOfOtherGroundStationsAndOurOwnEchoAreIgnored) {
  LinkSession s = openSession();
  mav::Heartbeat gcs = robotHeartbeat();
  gcs.type = static_cast<std::uint8_t>(mav::MavType::kGcs);
  s.onFrame(frameOf(gcs, 200, 190), 0.1);
  s.onFrame(frameOf(robotHeartbeat(), 255, 190), 0.2);  // our own system id
  EXPECT_EQ(s.state(), LinkState::kConnecting);
}

TEST(LinkSession, ConfiguredTargetSystemIgnoresOtherRobots) {
  LinkSession s = openSession({.target_system = 3});
  s.onFrame(frameOf(robotHeartbeat(), 1, 1), 0.1);
  EXPECT_EQ(s.state(), LinkState::kConnecting);
  s.onFrame(frameOf(robotHeartbeat(), 3, 1), 0.2);
  EXPECT_EQ(s.state(), LinkState::kConnected);
}

TEST(LinkSession, SilenceLosesTheLinkWithinTheTimeout) {
  LinkSession s = openSession({.timeout_s = 1.5});
  s.onFrame(frameOf(robotHeartbeat()), 0.5);
  s.takeOutput();
  const auto before = run(s, 0.5, 2.0);  // 1.5 s of silence: not yet
  EXPECT_EQ(s.state(), LinkState::kConnected);
  EXPECT_TRUE(eventsOf(before, LinkEventKind::kLinkLost).empty());
  s.tick(2.0 + kTick);
  EXPECT_EQ(s.state(), LinkState::kLost);
  const auto lost = eventsOf(s.takeOutput(), LinkEventKind::kLinkLost);
  ASSERT_EQ(lost.size(), 1u);
  EXPECT_NE(lost[0].text.find("no heartbeat"), std::string::npos);
  EXPECT_EQ(s.stats(2.1).link_losses, 1u);
}

TEST(LinkSession, RegularHeartbeatsKeepTheLinkUp) {
  LinkSession s = openSession({.timeout_s = 1.5});
  for (int i = 0; i < 10; ++i) {
    s.onFrame(frameOf(robotHeartbeat()), i * 1.0);
    run(s, i * 1.0, i * 1.0 + 1.0 - 1e-6);
  }
  EXPECT_EQ(s.state(), LinkState::kConnected);
  EXPECT_EQ(s.stats(10.0).link_losses, 0u);
}

TEST(LinkSession, TransportFailureWhileConnectedLosesTheLinkAtOnce) {
  LinkSession s = openSession();
  s.onFrame(frameOf(robotHeartbeat()), 0.1);
  s.onTransportDown(0.2, "cannot read /dev/ttyUSB0: device gone");
  EXPECT_EQ(s.state(), LinkState::kLost);
  const auto lost = eventsOf(s.takeOutput(), LinkEventKind::kLinkLost);
  ASSERT_EQ(lost.size(), 1u);
  EXPECT_NE(lost[0].text.find("device gone"), std::string::npos);
}

TEST(LinkSession, ReconnectsWhenHeartbeatsReturnAfterALoss) {
  LinkSession s = openSession({.timeout_s = 1.0});
  s.onFrame(frameOf(robotHeartbeat()), 0.0);
  run(s, 0.0, 1.5);
  ASSERT_EQ(s.state(), LinkState::kLost);
  s.onReconnecting(1.6, "no heartbeat");
  s.onTransportOpen(1.7, "reopened");
  EXPECT_EQ(messagesOf<mav::Heartbeat>(s.takeOutput()).size(), 1u);
  EXPECT_EQ(s.state(), LinkState::kLost);  // transport back, robot not yet
  s.onFrame(frameOf(robotHeartbeat()), 2.0);
  EXPECT_EQ(s.state(), LinkState::kConnected);
  const auto up = eventsOf(s.takeOutput(), LinkEventKind::kLinkUp);
  ASSERT_EQ(up.size(), 1u);
  EXPECT_NE(up[0].text.find("lost"), std::string::npos);
  const auto stats = s.stats(2.0);
  EXPECT_EQ(stats.reconnect_attempts, 1u);
  EXPECT_EQ(stats.link_losses, 1u);
}

TEST(LinkSession, CloseDisconnectsAndCancelsPendingCommands) {
  LinkSession s = openSession();
  std::optional<CommandResult> result;
  s.sendCommand(
      moveCommand(), [&](const CommandResult& r) { result = r; }, 0.0);
  s.close(0.1);
  EXPECT_EQ(s.state(), LinkState::kDisconnected);
  auto out = s.takeOutput();
  ASSERT_EQ(out.completed.size(), 1u);
  EXPECT_EQ(out.completed[0].result.outcome, CommandOutcome::kCancelled);
  EXPECT_EQ(eventsOf(out, LinkEventKind::kClosed).size(), 1u);
  EXPECT_TRUE(messagesOf<mav::Heartbeat>(run(s, 0.1, 3.0)).empty());
}

TEST(LinkSession, CommandOnAClosedLinkIsCancelledAtOnce) {
  LinkSession s;
  s.sendCommand(moveCommand(), {}, 0.0);
  auto out = s.takeOutput();
  EXPECT_TRUE(messagesOf<mav::CommandLong>(out).empty());
  ASSERT_EQ(out.completed.size(), 1u);
  EXPECT_NE(out.completed[0].result.message.find("link not open"), std::string::npos);
}

TEST(LinkSession, CommandIsRetriedUntilAcknowledged) {
  LinkSession s = openSession();
  s.onFrame(frameOf(robotHeartbeat()), 0.0);
  s.takeOutput();
  s.sendCommand(moveCommand(), {}, 0.0);
  auto first = messagesOf<mav::CommandLong>(s.takeOutput());
  ASSERT_EQ(first.size(), 1u);
  EXPECT_EQ(first[0].confirmation, 0);
  EXPECT_EQ(first[0].target_system, 1);  // filled in from the peer's heartbeat
  EXPECT_EQ(first[0].target_component, 1);
  const auto retries = messagesOf<mav::CommandLong>(run(s, 0.0, 0.7));
  ASSERT_EQ(retries.size(), 1u);  // at 0.5 s
  EXPECT_EQ(retries[0].confirmation, 1);

  mav::CommandAck ack;
  ack.command = first[0].command;
  ack.result = static_cast<std::uint8_t>(mav::MavResult::kAccepted);
  s.onFrame(frameOf(ack), 0.75);
  auto out = s.takeOutput();
  ASSERT_EQ(out.completed.size(), 1u);
  const auto& r = out.completed[0].result;
  EXPECT_EQ(r.outcome, CommandOutcome::kAccepted);
  EXPECT_EQ(r.attempts, 2);
  EXPECT_NEAR(r.elapsed_s, 0.75, 1e-9);
  EXPECT_EQ(r.message, "IRGS_MOVE_DISTANCE accepted (2 attempts, 0.75 s)");
  const auto events = eventsOf(out, LinkEventKind::kCommandResult);
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].text, r.message);
  EXPECT_TRUE(messagesOf<mav::CommandLong>(run(s, 0.75, 3.0)).empty());  // no more retries
}

TEST(LinkSession, CommandTimesOutAfterEveryAttemptWentUnanswered) {
  LinkSessionConfig config;
  config.commands.retry_s = 0.5;
  config.commands.max_attempts = 4;
  LinkSession s = openSession(config);
  std::optional<CommandResult> result;
  s.sendCommand(
      moveCommand(), [&](const CommandResult& r) { result = r; }, 0.0);
  s.takeOutput();
  auto out = run(s, 0.0, 1.95);
  EXPECT_EQ(messagesOf<mav::CommandLong>(out).size(), 3u);  // retries at 0.5, 1.0, 1.5
  EXPECT_TRUE(out.completed.empty());
  out = run(s, 1.95, 2.0);
  ASSERT_EQ(out.completed.size(), 1u);
  out.completed[0].callback(out.completed[0].result);  // the owner runs callbacks
  ASSERT_TRUE(result);
  EXPECT_EQ(result->outcome, CommandOutcome::kTimedOut);
  EXPECT_EQ(result->attempts, 4);
  EXPECT_FALSE(result->mav_result);
  EXPECT_EQ(result->message, "IRGS_MOVE_DISTANCE timed out: no COMMAND_ACK (4 attempts, 2.00 s)");
}

TEST(LinkSession, RejectedCommandReportsTheMavResult) {
  LinkSession s = openSession();
  s.sendCommand(moveCommand(), {}, 0.0);
  s.takeOutput();
  mav::CommandAck ack;
  ack.command = moveCommand().command;
  ack.result = static_cast<std::uint8_t>(mav::MavResult::kTemporarilyRejected);
  s.onFrame(frameOf(ack), 0.1);
  auto out = s.takeOutput();
  ASSERT_EQ(out.completed.size(), 1u);
  EXPECT_EQ(out.completed[0].result.outcome, CommandOutcome::kRejected);
  EXPECT_EQ(out.completed[0].result.mav_result,
            static_cast<std::uint8_t>(mav::MavResult::kTemporarilyRejected));
  EXPECT_NE(out.completed[0].result.message.find("rejected: TEMPORARILY_REJECTED"),
            std::string::npos);
}

TEST(LinkSession, TimesyncAnswerGivesTheRoundTripTime) {
  LinkSession s = openSession({.timesync_period_s = 1.0});
  EXPECT_FALSE(s.stats(0.0).rtt_s);
  s.onFrame(frameOf(robotHeartbeat()), 0.2);
  s.takeOutput();
  s.tick(0.25);
  const auto requests = messagesOf<mav::Timesync>(s.takeOutput());
  ASSERT_EQ(requests.size(), 1u);
  EXPECT_EQ(requests[0].tc1, 0);
  EXPECT_EQ(requests[0].target_system, 1);
  mav::Timesync reply;
  reply.tc1 = 123456789;
  reply.ts1 = requests[0].ts1;
  reply.target_system = 255;
  reply.target_component = 190;
  s.onFrame(frameOf(reply), 0.33);
  const auto stats = s.stats(0.33);
  ASSERT_TRUE(stats.rtt_s);
  EXPECT_NEAR(*stats.rtt_s, 0.08, 1e-6);
  EXPECT_NEAR(*stats.rtt_mean_s, 0.08, 1e-6);
  s.onFrame(frameOf(reply), 0.5);  // a duplicate answer is not a second sample
  EXPECT_NEAR(*s.stats(0.5).rtt_s, 0.08, 1e-6);
  EXPECT_EQ(messagesOf<mav::Timesync>(run(s, 0.33, 1.5)).size(), 1u);  // 1 s after the first
}

TEST(LinkSession, AnswersThePeersTimesyncRequests) {
  LinkSession s = openSession();
  mav::Timesync request;
  request.ts1 = 987654321;
  s.onFrame(frameOf(request, 1, 1), 2.0);
  const auto replies = messagesOf<mav::Timesync>(s.takeOutput());
  ASSERT_EQ(replies.size(), 1u);
  EXPECT_EQ(replies[0].ts1, 987654321);
  EXPECT_EQ(replies[0].tc1, 2'000'000'000);
  EXPECT_EQ(replies[0].target_system, 1);
}

TEST(LinkSession, StatisticsCountRatesErrorsAndLoss) {
  LinkSession s = openSession({.stats_window_s = 2.0});
  mav::DecodeCounters delta;
  delta.frames = 9;
  delta.sequence_gaps = 1;
  delta.bad_crc = 2;
  delta.unknown_id = 3;
  for (int i = 0; i < 10; ++i) {
    s.onReceived(100, delta, 0.1 * i);  // 1000 bytes over 1 s
    s.onSent(20, 0.1 * i);
  }
  s.onFrame(frameOf(robotHeartbeat()), 0.95);
  const auto stats = s.stats(1.0);
  EXPECT_EQ(stats.rx_bytes, 1000u);
  EXPECT_EQ(stats.tx_bytes, 200u);
  EXPECT_EQ(stats.tx_messages, 10u);
  EXPECT_EQ(stats.rx_messages, 1u);
  EXPECT_DOUBLE_EQ(stats.rx_bytes_per_s, 500.0);  // 1000 bytes / 2 s window
  EXPECT_DOUBLE_EQ(stats.tx_messages_per_s, 5.0);
  EXPECT_EQ(stats.crc_errors, 20u);
  EXPECT_EQ(stats.sequence_errors, 10u);
  EXPECT_EQ(stats.other_errors, 30u);
  EXPECT_DOUBLE_EQ(stats.loss_percent, 10.0);
  ASSERT_TRUE(stats.since_heartbeat_s);
  EXPECT_NEAR(*stats.since_heartbeat_s, 0.05, 1e-9);
  const auto later = s.stats(5.0);  // the window slid past all traffic
  EXPECT_DOUBLE_EQ(later.rx_bytes_per_s, 0.0);
  EXPECT_DOUBLE_EQ(later.loss_percent, 0.0);
  EXPECT_EQ(later.rx_bytes, 1000u);
}

TEST(LinkSession, StatusTextBecomesAConsoleEvent) {
  LinkSession s = openSession();
  mav::Statustext st;
  st.severity = static_cast<std::uint8_t>(mav::MavSeverity::kWarning);
  const std::string text = "bumper\tpressed";
  std::copy(text.begin(), text.end(), st.text.begin());
  s.onFrame(frameOf(st), 1.0);
  const auto events = eventsOf(s.takeOutput(), LinkEventKind::kStatusText);
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].text, "[1] bumper?pressed");
  EXPECT_EQ(events[0].severity, static_cast<std::uint8_t>(mav::MavSeverity::kWarning));
}

TEST(LinkSession, StatusTextFillingAllFiftyCharactersIsKeptWhole) {
  LinkSession s = openSession();
  mav::Statustext st;
  st.text.fill('x');
  s.onFrame(frameOf(st), 1.0);
  const auto events = eventsOf(s.takeOutput(), LinkEventKind::kStatusText);
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].text, "[1] " + std::string(50, 'x'));
}

TEST(LinkSession, RejectsNonsenseConfiguration) {
  EXPECT_THROW(LinkSession({.heartbeat_period_s = 0.0}), std::invalid_argument);
  EXPECT_THROW(LinkSession({.timeout_s = -1.0}), std::invalid_argument);
  EXPECT_THROW(LinkSession({.stats_window_s = 0.0}), std::invalid_argument);
}

}  // namespace
}  // namespace irgs::comms
