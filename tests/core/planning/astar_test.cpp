#include "core/planning/astar.hpp"

#include <gtest/gtest.h>

#include <random>

namespace irgs {
namespace {

// Random map: random rectangles plus scattered single cells, seeded.
PlanningGrid randomMap(int w, int h, double density, std::mt19937_64& rng) {
  PlanningGrid g = PlanningGrid::freeGrid(w, h, 0.05);
  std::uniform_int_distribution<int> col(0, w - 1), row(0, h - 1), side(1, 6);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const auto target = static_cast<std::size_t>(density * static_cast<double>(g.cellCount()));
  while (g.blockedCount() < target) {
    const int c0 = col(rng), r0 = row(rng);
    const int cw = u(rng) < 0.3 ? 1 : side(rng), rh = u(rng) < 0.3 ? 1 : side(rng);
    for (int r = r0; r < std::min(h, r0 + rh); ++r)
      for (int c = c0; c < std::min(w, c0 + cw); ++c)
        g.setBlocked({c, r}, true);
  }
  return g;
}

// Every step of the path is a legal move: 8-connected, free cells, no corner cutting, and the
// step costs add up to the reported cost.
void expectValidPath(const PlanningGrid& g, const PlanResult& r) {
  ASSERT_FALSE(r.cells.empty());
  ASSERT_EQ(r.points.size(), r.cells.size());
  std::uint64_t cost = 0;
  for (std::size_t k = 0; k < r.cells.size(); ++k) {
    ASSERT_TRUE(g.isFree(r.cells[k]));
    if (k == 0)
      continue;
    const int dc = r.cells[k].col - r.cells[k - 1].col, dr = r.cells[k].row - r.cells[k - 1].row;
    ASSERT_TRUE(std::abs(dc) <= 1 && std::abs(dr) <= 1 && (dc != 0 || dr != 0));
    if (dc != 0 && dr != 0) {
      ASSERT_TRUE(g.isFree({r.cells[k - 1].col + dc, r.cells[k - 1].row}));
      ASSERT_TRUE(g.isFree({r.cells[k - 1].col, r.cells[k - 1].row + dr}));
      cost += kDiagonalCost;
    } else {
      cost += kStraightCost;
    }
  }
  EXPECT_EQ(cost, r.cost);
}

class AStarModes : public ::testing::TestWithParam<SearchMode> {};

TEST_P(AStarModes, CostEqualsDijkstraOnManyRandomMaps) {
  std::mt19937_64 rng(20261122);
  AStarPlanner planner;  // reused: exercises the generation counters
  AStarOptions options;
  options.mode = GetParam();
  int found = 0, unreachable = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const int w = 5 + trial % 37, h = 5 + (trial * 7) % 41;
    const PlanningGrid g = randomMap(w, h, 0.1 + 0.05 * (trial % 7), rng);
    std::uniform_int_distribution<int> col(0, w - 1), row(0, h - 1);
    for (int q = 0; q < 5; ++q) {
      const Cell s{col(rng), row(rng)}, t{col(rng), row(rng)};
      const PlanResult ref = dijkstraReference(g, s, t);
      const PlanResult r = planner.plan(g, s, t, options);
      ASSERT_EQ(r.status, ref.status) << "trial " << trial;
      if (ref.found()) {
        ASSERT_EQ(r.cost, ref.cost) << "trial " << trial;
        ASSERT_EQ(r.cells.front(), s);
        ASSERT_EQ(r.cells.back(), t);
        expectValidPath(g, r);
        ++found;
      } else if (ref.status == PlanStatus::kNoPath) {
        ++unreachable;
      }
    }
  }
  EXPECT_GT(found, 800);
  EXPECT_GT(unreachable, 20);
}

TEST_P(AStarModes, ReportsBlockedAndOutOfBoundsEnds) {
  PlanningGrid g = PlanningGrid::freeGrid(10, 10, 0.1);
  g.setBlocked({3, 3}, true);
  AStarOptions o;
  o.mode = GetParam();
  AStarPlanner p;
  EXPECT_EQ(p.plan(g, Cell{3, 3}, Cell{5, 5}, o).status, PlanStatus::kStartBlocked);
  EXPECT_EQ(p.plan(g, Cell{0, 0}, Cell{3, 3}, o).status, PlanStatus::kGoalBlocked);
  EXPECT_EQ(p.plan(g, Cell{-1, 0}, Cell{3, 4}, o).status, PlanStatus::kOutOfBounds);
  EXPECT_EQ(p.plan(g, Cell{0, 0}, Cell{10, 4}, o).status, PlanStatus::kOutOfBounds);
  EXPECT_EQ(p.plan(g, Vec2(-0.5, 0.2), Vec2(0.5, 0.5), o).status, PlanStatus::kOutOfBounds);
  EXPECT_EQ(p.plan(g, Vec2(NAN, 0.2), Vec2(0.5, 0.5), o).status, PlanStatus::kOutOfBounds);
  const PlanResult same = p.plan(g, Cell{4, 4}, Cell{4, 4}, o);
  EXPECT_EQ(same.status, PlanStatus::kFound);
  EXPECT_EQ(same.cells.size(), 1u);
  EXPECT_EQ(same.cost, 0u);
}

TEST_P(AStarModes, DoesNotCutCornersBetweenDiagonalBlocks) {
  // . #      the only diagonal step from (0,0) to (1,1) passes between two blocked cells
  // # .
  PlanningGrid g = PlanningGrid::freeGrid(2, 2, 0.1);
  g.setBlocked({1, 0}, true);
  g.setBlocked({0, 1}, true);
  AStarOptions o;
  o.mode = GetParam();
  EXPECT_EQ(planAStar(g, {0, 0}, {1, 1}, o).status, PlanStatus::kNoPath);
  g.setBlocked({1, 0}, false);  // one side open: still no diagonal step, two straight ones
  const PlanResult r = planAStar(g, {0, 0}, {1, 1}, o);
  ASSERT_TRUE(r.found());
  EXPECT_EQ(r.cost, 2 * kStraightCost);
  EXPECT_NEAR(r.cost_m, 0.2, 1e-9);
}

TEST_P(AStarModes, ExpansionBudgetReturnsPartialPathTowardsTheGoal) {
  PlanningGrid g = PlanningGrid::freeGrid(200, 200, 0.01);
  for (int r = 0; r < 190; ++r)
    g.setBlocked({100, r}, true);  // a wall to go around
  AStarOptions o;
  o.mode = GetParam();
  o.budget.max_expansions = 5;
  const PlanResult r = planAStar(g, {0, 0}, {199, 0}, o);
  EXPECT_EQ(r.status, PlanStatus::kPartial);
  EXPECT_EQ(r.expansions, 5u);
  ASSERT_FALSE(r.cells.empty());
  EXPECT_EQ(r.cells.front(), (Cell{0, 0}));
  EXPECT_LT(octileCost(r.cells.back(), {199, 0}), octileCost({0, 0}, {199, 0}));
  expectValidPath(g, r);
}

TEST_P(AStarModes, TimeBudgetUsesTheInjectedClock) {
  PlanningGrid g = PlanningGrid::freeGrid(300, 300, 0.01);
  for (int r = 0; r < 299; ++r)
    g.setBlocked({150, r}, true);
  double t = 0.0;
  AStarOptions o;
  o.mode = GetParam();
  o.budget.max_time_s = 1.0;
  o.budget.check_interval = 1;
  o.budget.now_s = [&t] { return t += 0.25; };  // every poll advances the fake clock
  const PlanResult r = planAStar(g, {0, 0}, {299, 0}, o);
  EXPECT_EQ(r.status, PlanStatus::kPartial);
  EXPECT_LE(r.expansions, 5u);
  EXPECT_FALSE(r.cells.empty());
}

TEST_P(AStarModes, CancelHookStopsTheSearch) {
  const PlanningGrid g = PlanningGrid::freeGrid(100, 100, 0.01);
  AStarOptions o;
  o.mode = GetParam();
  int polls = 0;
  o.budget.check_interval = 1;
  // The first poll happens before the search, the second after the first expansion.
  o.budget.cancelled = [&polls] { return ++polls > 1; };
  const PlanResult r = planAStar(g, {0, 0}, {99, 57}, o);
  EXPECT_EQ(r.status, PlanStatus::kCancelled);
  EXPECT_TRUE(r.cells.empty());
  o.budget.cancelled = [] { return true; };
  EXPECT_EQ(planAStar(g, {0, 0}, {99, 57}, o).status, PlanStatus::kCancelled);
}

TEST_P(AStarModes, ExpansionLogListsExpandedCellsInOrder) {
  const PlanningGrid g = PlanningGrid::freeGrid(30, 30, 0.01);
  AStarOptions o;
  o.mode = GetParam();
  o.record_expansions = true;
  const PlanResult r = planAStar(g, {2, 3}, {25, 20}, o);
  ASSERT_TRUE(r.found());
  ASSERT_EQ(r.expanded.size(), r.expansions);
  EXPECT_EQ(r.expanded.front(), (Cell{2, 3}));
  EXPECT_EQ(r.expanded.back(), (Cell{25, 20}));
}

TEST_P(AStarModes, RegionMaskConfinesTheSearch) {
  const PlanningGrid g = PlanningGrid::freeGrid(20, 10, 0.01);
  std::vector<std::int32_t> region(g.cellCount(), 0);
  for (int r = 0; r < 10; ++r)
    for (int c = 0; c < 20; ++c)
      region[g.index({c, r})] = (c == 10 && r > 0) ? 1 : 0;  // a fence except at row 0
  AStarOptions o;
  o.mode = GetParam();
  o.region_of_cell = &region;
  o.region = 0;
  const PlanResult r = planAStar(g, {5, 9}, {15, 9}, o);
  ASSERT_TRUE(r.found());
  for (const Cell& c : r.cells)
    EXPECT_EQ(region[g.index(c)], 0);
  EXPECT_EQ(planAStar(g, {10, 5}, {15, 9}, o).status, PlanStatus::kStartBlocked);
  const std::vector<std::int32_t> wrong(3, 0);
  o.region_of_cell = &wrong;
  EXPECT_THROW(planAStar(g, {0, 0}, {1, 1}, o), std::invalid_argument);
}

INSTANTIATE_TEST_SUITE_P(Modes, AStarModes,
                         ::testing::Values(SearchMode::kJumpPoints, SearchMode::kPlain),
                         [](const auto& param_info) {
                           return param_info.param == SearchMode::kPlain
                                      ? std::string("Plain")
                                      : std::string("JumpPoints");
                         });

TEST(AStar, RejectsATimeBudgetWithoutAClock) {
  const PlanningGrid g = PlanningGrid::freeGrid(4, 4, 0.01);
  AStarOptions o;
  o.budget.max_time_s = 0.1;
  EXPECT_THROW(planAStar(g, {0, 0}, {3, 3}, o), std::invalid_argument);
  o.budget.max_time_s = -1.0;
  EXPECT_THROW(planAStar(g, {0, 0}, {3, 3}, o), std::invalid_argument);
}

TEST(AStar, StatusNamesAreReadable) {
  EXPECT_EQ(toString(PlanStatus::kGoalBlocked), "goal blocked");
  EXPECT_EQ(toString(PlanStatus::kPartial), "partial");
}

}  // namespace
}  // namespace irgs
