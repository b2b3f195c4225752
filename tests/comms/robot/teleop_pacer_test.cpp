#include "comms/robot/teleop_pacer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <ostream>
#include <vector>

namespace irgs::comms {
namespace {

struct Sent {
  double t;
  std::int16_t x;
  std::int16_t r;
  friend bool operator==(const Sent&, const Sent&) = default;
};
void PrintTo(const Sent& s, std::ostream* os) {
  *os << s.t << " x=" << s.x << " r=" << s.r;
}

// The MANUAL_CONTROLs a caller gets when it calls want() with `axes(t)` every `call_ms` and
// LinkedRobot's 10 ms timer polls next(), from 0 to end_s.
template <typename Axes>
std::vector<Sent> run(TeleopPacer& pacer, double end_s, int call_ms, Axes axes) {
  std::vector<Sent> out;
  for (int ms = 0; ms <= std::lround(end_s * 1000); ++ms) {
    const double t = ms / 1000.0;
    if (ms % call_ms == 0) {
      pacer.want(axes(t));
      if (auto a = pacer.next(t))  // drive() sends at once when it may
        out.push_back({t, a->x, a->r});
    }
    if (ms % 10 == 0) {
      if (auto a = pacer.next(t))
        out.push_back({t, a->x, a->r});
    }
  }
  return out;
}

TEST(TeleopPacer, SendsAChangeAtOnceAndRepeatsAHeldCommandAtTenHertz) {
  TeleopPacer pacer;
  const auto sent = run(pacer, 0.35, 50, [](double t) {
    return TeleopAxes{static_cast<std::int16_t>(t < 0.1 ? 500 : 300), 0};
  });
  EXPECT_EQ(sent, (std::vector<Sent>{{0.0, 500, 0}, {0.1, 300, 0}, {0.2, 300, 0}, {0.3, 300, 0}}));
  EXPECT_EQ(pacer.stats().repeats, 2u);
}

TEST(TeleopPacer, ACallerAskingEveryMillisecondGetsAtMostOneMessagePer55Ms) {
  TeleopPacer pacer;
  // A new turn rate every millisecond for 2 s: the newest goes every 55-60 ms (the 10 ms timer).
  const auto sent = run(pacer, 2.0, 1, [](double t) {
    return TeleopAxes{400, static_cast<std::int16_t>(std::lround(t * 1000) % 1000)};
  });
  ASSERT_GE(sent.size(), 30u);
  EXPECT_LE(sent.size(), 37u);  // 2 s / 55 ms + the first
  for (std::size_t i = 1; i < sent.size(); ++i) {
    EXPECT_GE(sent[i].t - sent[i - 1].t, 0.055 - 1e-9);
    // What goes is the newest wanted at that instant, not a stale one.
    EXPECT_EQ(sent[i].r, std::lround(sent[i].t * 1000) % 1000);
  }
  int peak = 0;
  for (std::size_t i = 0; i < sent.size(); ++i) {
    int n = 0;
    for (std::size_t j = i; j < sent.size() && sent[j].t < sent[i].t + 1.0; ++j)
      ++n;
    peak = std::max(peak, n);
  }
  EXPECT_LE(peak, 20);  // issue 24's cap, with room to spare
  EXPECT_GT(pacer.stats().coalesced, 1900u);
}

TEST(TeleopPacer, AStopGoesOnceAndThenNothingIsRepeated) {
  TeleopPacer pacer;
  const auto sent = run(pacer, 0.6, 10, [](double t) {
    return t < 0.2 ? TeleopAxes{0, -250} : TeleopAxes{};
  });
  EXPECT_EQ(sent, (std::vector<Sent>{{0.0, 0, -250}, {0.1, 0, -250}, {0.2, 0, 0}}));
}

TEST(TeleopPacer, AStopRightAfterAChangeWaitsOutTheIntervalButIsNotLost) {
  TeleopPacer pacer;
  pacer.want({600, 0});
  ASSERT_TRUE(pacer.next(0.0));
  pacer.want({});
  EXPECT_FALSE(pacer.next(0.02));
  EXPECT_FALSE(pacer.next(0.05));
  const auto stop = pacer.next(0.055);
  ASSERT_TRUE(stop);
  EXPECT_TRUE(stop->zero());
}

TEST(TeleopPacer, NothingGoesBeforeTheFirstMotionOrAfterACancel) {
  TeleopPacer pacer;
  pacer.want({});
  EXPECT_FALSE(pacer.next(0.0));
  pacer.want({100, 0});
  pacer.cancel();  // a behaviour took over before the command went
  EXPECT_FALSE(pacer.next(0.1));
  EXPECT_FALSE(pacer.next(0.5));
  pacer.want({100, 0});  // driving again is a change
  EXPECT_TRUE(pacer.next(0.6));
}

TEST(TeleopPacer, RejectsAnIntervalLongerThanTheRepeatPeriod) {
  EXPECT_THROW(TeleopPacer({0.1, 0.2}), std::invalid_argument);
  EXPECT_THROW(TeleopPacer({0.1, 0.0}), std::invalid_argument);
}

}  // namespace
}  // namespace irgs::comms
