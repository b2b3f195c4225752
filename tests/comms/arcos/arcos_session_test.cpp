#include "comms/arcos/arcos_session.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "comms/arcos/arcos_commands.hpp"

namespace irgs::comms::arcos {
namespace {

using Bytes = std::vector<std::uint8_t>;

Packet packetOf(const Bytes& payload) {
  Packet p;
  std::copy(payload.begin(), payload.end(), p.bytes.begin());
  p.size = payload.size();
  return p;
}

// The command numbers of the packets the session wants to send.
std::vector<int> commandsOf(const std::vector<Bytes>& packets) {
  std::vector<int> out;
  for (const Bytes& p : packets)
    out.push_back(p.at(3));
  return out;
}

Bytes sipPayload() {
  StandardSip sip;
  sip.sonars.push_back({0, 500});
  return encodeStandardSip(sip);
}

// What the session sends while ticked every 10 ms over (from_s, to_s].
std::vector<int> commandsWhileTicking(ArcosClientSession& session, double from_s, double to_s) {
  std::vector<int> out;
  for (int k = 1; from_s + k * 0.01 <= to_s + 1e-9; ++k) {
    session.tick(from_s + k * 0.01);
    for (int c : commandsOf(session.takeOutgoing()))
      out.push_back(c);
  }
  return out;
}

void handshake(ArcosClientSession& session, double& t) {
  session.start(t);
  session.onPacket(packetOf({0}), t += 0.01);
  session.onPacket(packetOf({1}), t += 0.01);
  session.onPacket(packetOf(encodeSync2Reply({"MobileSim", "Pioneer", "p3dx"})), t += 0.01);
  session.onPacket(packetOf(sipPayload()), t += 0.1);
}

TEST(ArcosClientSession, PerformsTheSyncHandshakeThenOpensEnablesAndKeepsTheWatchdogFed) {
  ArcosClientSession session;
  double t = 0.0;
  session.start(t);
  EXPECT_EQ(commandsOf(session.takeOutgoing()), (std::vector<int>{0}));  // SYNC0
  session.onPacket(packetOf({0}), t += 0.01);
  EXPECT_EQ(commandsOf(session.takeOutgoing()), (std::vector<int>{1}));  // SYNC1
  session.onPacket(packetOf({1}), t += 0.01);
  EXPECT_EQ(commandsOf(session.takeOutgoing()), (std::vector<int>{2}));  // SYNC2
  session.onPacket(packetOf(encodeSync2Reply({"MobileSim", "Pioneer", "p3dx"})), t += 0.01);
  // OPEN at once; ENABLE and SONAR follow one packet at a time, paced by the scheduler.
  EXPECT_EQ(commandsOf(session.takeOutgoing()), (std::vector<int>{1}));
  EXPECT_EQ(session.state(), ArcosState::kOpening);
  EXPECT_EQ(commandsWhileTicking(session, t, t + 0.01), (std::vector<int>{}));  // the 20 ms gap
  EXPECT_EQ(commandsWhileTicking(session, t + 0.01, t + 0.3), (std::vector<int>{4, 28}));
  t += 0.3;
  ASSERT_TRUE(session.identity());
  EXPECT_EQ(session.identity()->subclass, "p3dx");
  session.onPacket(packetOf(sipPayload()), t += 0.1);
  EXPECT_EQ(session.state(), ArcosState::kConnected);
  EXPECT_EQ(session.takeSips().size(), 1u);
  // Nothing else to say: PULSE once nothing went out for keepalive_s (0.5 s).
  session.tick(t += 0.6);
  EXPECT_EQ(commandsOf(session.takeOutgoing()), (std::vector<int>{0}));
}

TEST(ArcosClientSession, ResendsAnUnansweredSyncAndStartsOverAfterTooManyAttempts) {
  ArcosSessionConfig config;
  config.max_sync_attempts = 3;
  ArcosClientSession session(config);
  double t = 0.0;
  session.start(t);
  session.onPacket(packetOf({0}), t += 0.01);  // SYNC0 answered, SYNC1 goes unanswered
  session.takeOutgoing();
  std::vector<int> sent;
  for (int i = 0; i < 3; ++i) {
    session.tick(t += config.sync_retry_s + 0.01);
    const auto commands = commandsOf(session.takeOutgoing());
    sent.insert(sent.end(), commands.begin(), commands.end());
  }
  // Two more SYNC1, then CLOSE and SYNC0 again.
  EXPECT_EQ(sent, (std::vector<int>{1, 1, 2, 0}));
}

// Over a late link (here 0.25 s each way) a SYNC resent every 0.3 s reaches the robot after
// the robot already answered it; a second SYNC2 then arrives as CLOSE once the robot is
// synchronised, and the connection never opens. The first echo shows the round trip: later
// SYNCs wait 2.5 of them before a resend.
TEST(ArcosClientSession, WaitsTheMeasuredRoundTripBeforeResendingASyncOverALateLink) {
  ArcosClientSession session;
  session.start(0.0);
  EXPECT_EQ(commandsOf(session.takeOutgoing()), (std::vector<int>{0}));
  EXPECT_EQ(commandsWhileTicking(session, 0.0, 0.5), (std::vector<int>{0}));  // 0.3 s: resent
  session.onPacket(packetOf({0}), 0.5);  // the first SYNC0's echo: round trip 0.5 s at most
  EXPECT_EQ(commandsOf(session.takeOutgoing()), (std::vector<int>{1}));
  session.onPacket(packetOf({0}), 0.8);  // the resend's echo: ignored
  EXPECT_EQ(commandsWhileTicking(session, 0.8, 1.0), (std::vector<int>{}));
  session.onPacket(packetOf({1}), 1.0);
  EXPECT_EQ(commandsOf(session.takeOutgoing()), (std::vector<int>{2}));
  // No second SYNC2 before 1.0 + 2.5 x 0.5 s; the reply comes at 1.5 s.
  EXPECT_EQ(commandsWhileTicking(session, 1.0, 1.5), (std::vector<int>{}));
  session.onPacket(packetOf(encodeSync2Reply({"MobileSim", "Pioneer", "p3dx"})), 1.5);
  EXPECT_EQ(commandsOf(session.takeOutgoing()), (std::vector<int>{1}));  // OPEN
  EXPECT_EQ(session.state(), ArcosState::kOpening);
}

TEST(ArcosClientSession, StillResendsAnUnansweredSyncAfterTheMeasuredRoundTrips) {
  ArcosClientSession session;
  session.start(0.0);
  session.takeOutgoing();
  session.onPacket(packetOf({0}), 0.4);  // round trip 0.4 s: resends after 1.0 s
  session.takeOutgoing();
  EXPECT_EQ(commandsWhileTicking(session, 0.4, 1.35), (std::vector<int>{}));
  EXPECT_EQ(commandsWhileTicking(session, 1.35, 1.45), (std::vector<int>{1}));
}

TEST(ArcosClientSession, ClosesAStillRunningServerThatAnswersSyncWithSips) {
  ArcosClientSession session;
  session.start(0.0);
  session.takeOutgoing();
  session.onPacket(packetOf(sipPayload()), 0.05);
  EXPECT_EQ(commandsOf(session.takeOutgoing()), (std::vector<int>{2}));  // CLOSE
  EXPECT_EQ(session.state(), ArcosState::kSyncing);
}

TEST(ArcosClientSession, DetectsLostSipsAndResynchronisesOnItsOwn) {
  ArcosClientSession session;
  double t = 0.0;
  handshake(session, t);
  session.takeEvents();
  session.takeOutgoing();
  session.tick(t += 1.0);
  EXPECT_EQ(session.state(), ArcosState::kConnected);
  session.tick(t += 0.6);  // 1.6 s without a SIP
  EXPECT_EQ(session.state(), ArcosState::kSyncing);
  EXPECT_EQ(session.stats().losses, 1u);
  const auto events = session.takeEvents();
  ASSERT_GE(events.size(), 1u);
  EXPECT_EQ(events[0].state, ArcosState::kLost);
  EXPECT_TRUE(events[0].warning);
  handshake(session, t);
  EXPECT_EQ(session.state(), ArcosState::kConnected);
  EXPECT_EQ(session.stats().handshakes, 2u);
}

TEST(ArcosClientSession, CountsAndSkipsABrokenSip) {
  ArcosClientSession session;
  double t = 0.0;
  handshake(session, t);
  session.takeSips();
  session.onPacket(packetOf({0x32, 1, 2}), t += 0.1);
  EXPECT_EQ(session.stats().bad_sips, 1u);
  EXPECT_TRUE(session.takeSips().empty());
  EXPECT_EQ(session.state(), ArcosState::kConnected);
}

TEST(ArcosClientSession, SendsCommandsOnlyWhileOpenAndClosesOnStop) {
  ArcosClientSession session;
  session.sendCommand(commandPayload(Command::kVel, 100));
  EXPECT_TRUE(session.takeOutgoing().empty());
  double t = 0.0;
  handshake(session, t);
  session.takeOutgoing();
  EXPECT_EQ(commandsWhileTicking(session, t, t + 0.3), (std::vector<int>{4, 28}));
  t += 0.3;
  session.sendCommand(commandPayload(Command::kSetO));
  session.pump(t);
  EXPECT_EQ(commandsOf(session.takeOutgoing()), (std::vector<int>{7}));
  session.stop(t);
  EXPECT_EQ(commandsOf(session.takeOutgoing()), (std::vector<int>{2}));
  EXPECT_EQ(session.state(), ArcosState::kDisconnected);
}

}  // namespace
}  // namespace irgs::comms::arcos
