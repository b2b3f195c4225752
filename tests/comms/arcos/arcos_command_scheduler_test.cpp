#include "comms/arcos/arcos_command_scheduler.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <ostream>
#include <string>
#include <vector>

namespace irgs::comms::arcos {
namespace {

using Bytes = std::vector<std::uint8_t>;

// "VEL 200", "PULSE", ... for a framed command packet: the literal sequences below read as the
// robot would log them.
std::string describe(const Bytes& packet) {
  const int number = packet.at(3);
  std::string name;
  switch (number) {
    case 0:
      name = "PULSE";
      break;
    case 4:
      name = "ENABLE";
      break;
    case 8:
      name = "MOVE";
      break;
    case 11:
      name = "VEL";
      break;
    case 12:
      name = "HEAD";
      break;
    case 13:
      name = "DHEAD";
      break;
    case 21:
      name = "RVEL";
      break;
    case 28:
      name = "SONAR";
      break;
    case 29:
      name = "STOP";
      break;
    case 55:
      name = "ESTOP";
      break;
    default:
      name = "#" + std::to_string(number);
  }
  if (packet.size() == 9) {
    const int magnitude = packet[5] | packet[6] << 8;
    name += " " + std::to_string(packet[4] == kArgNegative ? -magnitude : magnitude);
  }
  return name;
}

struct Sent {
  double t;
  std::string what;
  friend bool operator==(const Sent&, const Sent&) = default;
};
void PrintTo(const Sent& s, std::ostream* os) {
  *os << s.t << " " << s.what;
}

// Ticks every 10 ms (the owner's tick is 20 ms; finer here to show when a packet becomes due)
// from `from_s` up to `to_s`, collecting what goes out; `before_tick` runs first at each tick.
std::vector<Sent> run(ArcosCommandScheduler& s, double from_s, double to_s,
                      const std::function<void(double)>& before_tick = {}) {
  std::vector<Sent> out;
  for (long k = std::lround(from_s * 100); k <= std::lround(to_s * 100); ++k) {
    const double t = static_cast<double>(k) / 100.0;
    if (before_tick)
      before_tick(t);
    while (auto packet = s.next(t))
      out.push_back({t, describe(*packet)});
  }
  return out;
}

TEST(ArcosCommandScheduler, SendsASlotValueOnlyWhenItChanges) {
  ArcosCommandScheduler s;
  const std::vector<Sent> sent = run(s, 0.0, 0.4, [&](double t) {
    s.want({Command::kVel, t < 0.2 ? 200 : 250});  // wanted at every tick, changed once
  });
  EXPECT_EQ(sent, (std::vector<Sent>{{0.0, "VEL 200"}, {0.2, "VEL 250"}}));
  EXPECT_EQ(s.stats().changes, 2u);
}

TEST(ArcosCommandScheduler, TheNewestValueWinsWhileTheCapHoldsItBack) {
  ArcosCommandScheduler s;
  // A behaviour answering every 2 ms with a new turn rate: the first two go (the burst), then
  // one packet per 110 ms carries the newest value; the ones in between never go.
  std::vector<Sent> sent;
  for (int ms = 0; ms <= 250; ms += 2) {
    const double t = ms / 1000.0;
    s.want({Command::kRVel, ms});
    if (ms % 10 == 0) {
      while (auto packet = s.next(t))
        sent.push_back({t, describe(*packet)});
    }
  }
  EXPECT_EQ(sent,
            (std::vector<Sent>{
                {0.00, "RVEL 0"}, {0.02, "RVEL 20"}, {0.11, "RVEL 110"}, {0.22, "RVEL 220"}}));
  EXPECT_GT(s.stats().coalesced, 100u);
}

TEST(ArcosCommandScheduler, NeverMoreThanTenPacketsInAnySecondWhateverTheCallerDoes) {
  ArcosCommandScheduler s;
  std::vector<double> times;
  // 20 s of a flood: both slots change every 2 ms, one-shots and stops now and then.
  for (int ms = 0; ms <= 20000; ms += 2) {
    const double t = ms / 1000.0;
    s.want({Command::kVel, ms % 700});
    s.want({Command::kRVel, -(ms % 90)});
    if (ms % 500 == 0)
      s.sendOnce(commandPayload(Command::kSonar, 1));
    if (ms % 1300 == 0)
      s.sendUrgent(Command::kStop);
    while (auto packet = s.next(t))
      times.push_back(t);
  }
  int peak = 0;
  for (std::size_t i = 0; i < times.size(); ++i) {
    int in_second = 0;
    for (std::size_t j = i; j < times.size() && times[j] < times[i] + 1.0; ++j)
      ++in_second;
    peak = std::max(peak, in_second);
  }
  EXPECT_LE(peak, 10);
  EXPECT_GE(peak, 9);  // and the cap is used, not starved
  for (std::size_t i = 1; i < times.size(); ++i)
    EXPECT_GE(times[i] - times[i - 1], 0.02 - 1e-9) << "at " << times[i];
  EXPECT_LE(times.size(), 20 * 10 + 1u);
}

TEST(ArcosCommandScheduler, KeepsTheWatchdogFedWithRefreshesOrPulse) {
  ArcosCommandScheduler s;
  // Nothing wanted yet: PULSE every keepalive_s (0.5 s), counted from the first call.
  EXPECT_EQ(run(s, 0.0, 1.0), (std::vector<Sent>{{0.5, "PULSE"}, {1.0, "PULSE"}}));
  // Set points in effect: each is re-sent in turn instead (a lost one is recovered within 1 s).
  s.want({Command::kVel, 300});
  s.want({Command::kRVel, -15});
  EXPECT_EQ(run(s, 1.1, 3.2), (std::vector<Sent>{{1.1, "VEL 300"},
                                                 {1.12, "RVEL -15"},
                                                 {1.62, "VEL 300"},
                                                 {2.12, "RVEL -15"},
                                                 {2.62, "VEL 300"},
                                                 {3.12, "RVEL -15"}}));
  EXPECT_EQ(s.stats().refreshes, 4u);
}

TEST(ArcosCommandScheduler, RelativeMotionIsANewRequestEachTimeAndNeverRepeated) {
  ArcosCommandScheduler s;
  s.want({Command::kMove, 500});
  s.want({Command::kDHead, 15});
  EXPECT_EQ(run(s, 0.0, 0.1), (std::vector<Sent>{{0.0, "MOVE 500"}, {0.02, "DHEAD 15"}}));
  s.want({Command::kDHead, 15});  // another 15 degrees
  // The DHEAD goes; then PULSE is the keep-alive: re-sending MOVE or DHEAD would move again.
  EXPECT_EQ(run(s, 0.2, 1.3),
            (std::vector<Sent>{{0.2, "DHEAD 15"}, {0.7, "PULSE"}, {1.2, "PULSE"}}));
  // HEAD is absolute: it is repeatable, and it replaces the DHEAD in its slot.
  s.want({Command::kHead, 90});
  EXPECT_EQ(run(s, 1.4, 2.0), (std::vector<Sent>{{1.4, "HEAD 90"}, {1.9, "HEAD 90"}}));
  EXPECT_EQ(s.wanted(MotionSlot::kTranslational), (SlotCommand{Command::kMove, 500}));
}

TEST(ArcosCommandScheduler, OneShotsGoInOrderBeforeSlotChangesAndStopJumpsTheQueue) {
  ArcosCommandScheduler s;
  s.want({Command::kVel, 200});
  s.sendOnce(commandPayload(Command::kEnable, 1));
  s.sendOnce(commandPayload(Command::kSonar, 1));
  ASSERT_EQ(describe(*s.next(0.0)), "ENABLE 1");
  s.sendUrgent(Command::kStop);  // also drops the VEL 200 that has not gone yet
  EXPECT_EQ(run(s, 0.01, 0.5), (std::vector<Sent>{{0.02, "STOP"}, {0.11, "SONAR 1"}}));
  EXPECT_EQ(s.wanted(MotionSlot::kTranslational), (SlotCommand{Command::kVel, 0}));
  EXPECT_EQ(s.wanted(MotionSlot::kRotational), (SlotCommand{Command::kRVel, 0}));
  // Set points at zero after the STOP: wanting zero again sends nothing.
  s.want({Command::kVel, 0});
  EXPECT_TRUE(s.idle());
}

TEST(ArcosCommandScheduler, AStopIsNotRepeatedUntilSomethingMovesAgain) {
  ArcosCommandScheduler s;
  s.want({Command::kVel, 200});
  std::vector<Sent> sent = run(s, 0.0, 0.3, [&](double) { s.sendUrgent(Command::kStop); });
  EXPECT_EQ(sent, (std::vector<Sent>{{0.0, "STOP"}}));
  s.want({Command::kVel, 100});
  s.sendUrgent(Command::kStop);
  EXPECT_EQ(run(s, 0.4, 0.4), (std::vector<Sent>{{0.4, "STOP"}}));
  // An ESTOP always goes (once while one is waiting).
  s.sendUrgent(Command::kEStop);
  s.sendUrgent(Command::kEStop);
  EXPECT_EQ(run(s, 0.45, 0.5), (std::vector<Sent>{{0.45, "ESTOP"}}));
}

TEST(ArcosCommandScheduler, SpacesPacketsByTwiceTheirWireTimeOnASlowLink) {
  ArcosCommandSchedulerConfig config;
  config.baud = 1200;  // 120 bytes/s: a 9-byte VEL takes 75 ms on the wire
  ArcosCommandScheduler s(config);
  s.want({Command::kVel, 100});
  s.want({Command::kRVel, 10});
  EXPECT_EQ(run(s, 0.0, 0.2), (std::vector<Sent>{{0.0, "VEL 100"}, {0.15, "RVEL 10"}}));
  EXPECT_NEAR(s.gapLeft(0.2), 0.1, 1e-9);
}

TEST(ArcosCommandScheduler, AResetForgetsTheSlotsAndTheHistory) {
  ArcosCommandScheduler s;
  s.want({Command::kVel, 200});
  ASSERT_TRUE(s.next(0.0));
  s.reset();
  EXPECT_FALSE(s.wanted(MotionSlot::kTranslational));
  s.want({Command::kVel, 200});  // the same value is new on a new connection
  ASSERT_TRUE(s.next(0.001));    // and no gap is owed to the old one
  EXPECT_EQ(s.stats().packets, 2u);
}

TEST(ArcosCommandScheduler, RejectsWhatItCannotSchedule) {
  ArcosCommandScheduler s;
  EXPECT_THROW(s.want({Command::kSonar, 1}), std::invalid_argument);
  EXPECT_THROW(s.want({Command::kVel, 40000}), std::invalid_argument);
  EXPECT_THROW(s.sendUrgent(Command::kVel), std::invalid_argument);
  EXPECT_THROW(s.sendOnce({}), std::invalid_argument);
  ArcosCommandSchedulerConfig bad;
  bad.burst = 11;
  EXPECT_THROW(ArcosCommandScheduler{bad}, std::invalid_argument);
  bad = {};
  bad.min_gap_s = 0.0;
  EXPECT_THROW(ArcosCommandScheduler{bad}, std::invalid_argument);
}

}  // namespace
}  // namespace irgs::comms::arcos
