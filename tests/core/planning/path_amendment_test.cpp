#include "core/planning/path_amendment.hpp"

#include <gtest/gtest.h>

#include "core/planning/free_space.hpp"
#include "core/planning/traveling.hpp"
#include "core/planning/wave_points.hpp"

namespace irgs {
namespace {

// A Fig. 4.6-like layout (003_…): a 4 m x 4 m room at 5 cm cells with two boxes; the A* path
// from (4, 4) to (70, 70) is forced through two wave points off the diagonal (sub-map
// junctions), which costs extra turning points.
PlanningGrid roomWithBoxes() {
  PlanningGrid g = PlanningGrid::freeGrid(80, 80, 0.05);
  const auto box = [&g](int c0, int r0, int c1, int r1) {
    for (int r = r0; r <= r1; ++r)
      for (int c = c0; c <= c1; ++c)
        g.setBlocked({c, r}, true);
  };
  box(14, 0, 18, 20);   // a box in the left room
  box(60, 40, 64, 59);  // and one in the right room
  return g;
}

TEST(PathAmendment, ReducesTheWavePointTurnsOfAFig46LikeLayout) {
  const PlanningGrid g = roomWithBoxes();
  const WavePlan raw = planThroughWavePoints(g, {4, 4}, {70, 70}, {{30, 18}, {44, 60}});
  ASSERT_TRUE(raw.found());
  const int raw_turns = countTurns(raw.points);
  EXPECT_GE(raw_turns, 6);
  const AmendResult a = amendPath(g, raw.points, raw.wave_indices);
  EXPECT_EQ(a.turns_before, raw_turns);
  EXPECT_LE(a.turns_after, 3);
  EXPECT_LT(a.time_after_s, a.time_before_s);
  EXPECT_TRUE(polylineIsFree(g, a.points));
  EXPECT_EQ(a.points.front(), raw.points.front());
  EXPECT_EQ(a.points.back(), raw.points.back());
  // Every leg heads along a multiple of 15 degrees, as the robot turns.
  for (std::size_t i = 1; i < a.points.size(); ++i) {
    const Vec2 d = a.points[i] - a.points[i - 1];
    EXPECT_TRUE(headingOnQuantum(std::atan2(d.y(), d.x()), degToRad(15.0), degToRad(0.5)));
  }
}

TEST(PathAmendment, TriangleLegsModeAlsoStaysFreeAndDropsTurns) {
  const PlanningGrid g = roomWithBoxes();
  const WavePlan raw = planThroughWavePoints(g, {4, 4}, {70, 70}, {{30, 18}, {44, 60}});
  ASSERT_TRUE(raw.found());
  AmendOptions o;
  o.mode = AmendMode::kTriangleLegs;
  o.line_of_sight = false;
  const AmendResult a = amendPath(g, raw.points, raw.wave_indices, o);
  EXPECT_GE(a.wave_points_amended, 1);
  EXPECT_LT(a.turns_after, a.turns_before);
  EXPECT_TRUE(polylineIsFree(g, a.points));
}

TEST(PathAmendment, LeavesAPathUnchangedWhenNoTriangleIsFree) {
  // A corridor bend: the rectangle's both triangles cut the blocked inner corner.
  PlanningGrid g = PlanningGrid::freeGrid(20, 20, 0.1);
  for (int r = 0; r < 20; ++r)
    for (int c = 0; c < 20; ++c)
      g.setBlocked({c, r}, !(r <= 2 || c >= 17));
  const std::vector<Vec2> path{g.cellCentre({1, 1}), g.cellCentre({18, 1}), g.cellCentre({18, 18})};
  AmendOptions o;
  const AmendResult a = amendPath(g, path, {1}, o);
  EXPECT_EQ(a.points, path);
  EXPECT_EQ(a.turns_after, 1);
  EXPECT_THROW(amendPath(g, path, {3}, o), std::invalid_argument);
}

TEST(TravelTime, CountsStopsAndTurnAngles) {
  const std::vector<Vec2> l{{0.0, 0.0}, {1.0, 0.0}, {1.0, 1.0}};
  TravelTimeModel m;
  m.speed_mps = 0.5;
  m.turn_stop_s = 2.0;
  m.turn_rate_radps = kPi / 2.0;
  EXPECT_NEAR(travelTime(l, m), 4.0 + 2.0 + 1.0, 1e-12);
  EXPECT_NEAR(travelTime(l, m, kPi / 2.0), 4.0 + 2 * (2.0 + 1.0), 1e-12);
  m.speed_mps = 0.0;
  EXPECT_THROW(travelTime(l, m), std::invalid_argument);
}

TEST(Traveling, SplitsAtTurningPointsWithQuantisedTurns) {
  const std::vector<Vec2> p{{0.0, 0.0}, {0.5, 0.0}, {1.0, 0.0}, {1.0, 1.0}, {2.0, 2.0}};
  const TravelPlan t = makeTravelPlan(p, 0.0);
  ASSERT_EQ(t.segments.size(), 3u);
  EXPECT_NEAR(t.segments[0].turn_rad, 0.0, 1e-12);
  EXPECT_NEAR(t.segments[0].distance_m, 1.0, 1e-12);
  EXPECT_NEAR(t.segments[1].turn_rad, kPi / 2.0, 1e-12);
  EXPECT_NEAR(t.segments[2].turn_rad, -kPi / 4.0, 1e-12);
  EXPECT_NEAR(t.segments[2].distance_m, std::sqrt(2.0), 1e-12);
  EXPECT_EQ(t.turns, 2);
  EXPECT_NEAR(t.total_distance_m, 2.0 + std::sqrt(2.0), 1e-12);
  // 20 degrees rounds to the 15 degree quantum; the error is reported.
  const TravelPlan q =
      makeTravelPlan({{0.0, 0.0}, {std::cos(degToRad(20.0)), std::sin(degToRad(20.0))}}, 0.0);
  ASSERT_EQ(q.segments.size(), 1u);
  EXPECT_NEAR(q.segments[0].turn_rad, degToRad(15.0), 1e-12);
  EXPECT_NEAR(q.segments[0].heading_error_rad, degToRad(5.0), 1e-12);
  EXPECT_TRUE(makeTravelPlan({{1.0, 1.0}}, 0.0).segments.empty());
  EXPECT_THROW(makeTravelPlan({{NAN, 0.0}, {1.0, 0.0}}, 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace irgs
