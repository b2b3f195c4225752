#include "core/planning/wave_points.hpp"

#include <gtest/gtest.h>

#include <random>

#include "core/planning/free_space.hpp"

namespace irgs {
namespace {

TEST(WavePoints, RegionPathsAreFreeConnectedAndFoundWheneverDijkstraFindsOne) {
  std::mt19937_64 rng(99);
  int found = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const int w = 30 + trial % 31, h = 25 + (trial * 3) % 29;
    PlanningGrid g = PlanningGrid::freeGrid(w, h, 0.05);
    std::uniform_int_distribution<int> col(0, w - 1), row(0, h - 1), side(1, 5);
    while (g.blockedCount() < g.cellCount() / 5) {
      const int c0 = col(rng), r0 = row(rng), cw = side(rng), rh = side(rng);
      for (int r = r0; r < std::min(h, r0 + rh); ++r)
        for (int c = c0; c < std::min(w, c0 + cw); ++c)
          g.setBlocked({c, r}, true);
    }
    const PlanningGrid inflated = inflate(g, 0.03);
    const WaveRegions regions = partitionIntoBlocks(inflated, 8 + trial % 5);
    for (int q = 0; q < 5; ++q) {
      const Cell s{col(rng), row(rng)}, t{col(rng), row(rng)};
      const PlanResult ref = dijkstraReference(inflated, s, t);
      const WavePlan p = planWithWavePoints(inflated, regions, s, t);
      ASSERT_EQ(p.status, ref.status) << trial;
      if (!ref.found())
        continue;
      ++found;
      EXPECT_GE(p.cost, ref.cost);
      ASSERT_EQ(p.cells.front(), s);
      ASSERT_EQ(p.cells.back(), t);
      EXPECT_TRUE(polylineIsFree(inflated, p.points));  // collision-free with the inflated robot
      for (const std::size_t wi : p.wave_indices)
        ASSERT_LT(wi, p.cells.size());
    }
  }
  EXPECT_GT(found, 40);
}

TEST(WavePoints, EntrancesJoinDifferentRegionsAcrossBlockBorders) {
  const PlanningGrid g = PlanningGrid::freeGrid(20, 10, 0.1);
  const WaveRegions r = partitionIntoBlocks(g, 10);
  EXPECT_EQ(r.region_count, 2);
  ASSERT_EQ(r.entrances.size(), 1u);  // one run along the shared border, one wave point
  EXPECT_NE(r.entrances[0].region_a, r.entrances[0].region_b);
  EXPECT_EQ(r.entrances[0].a.col, 9);
  EXPECT_EQ(r.entrances[0].b.col, 10);
  const WavePlan p = planWithWavePoints(g, r, {1, 1}, {18, 8});
  ASSERT_TRUE(p.found());
  ASSERT_EQ(p.wave_indices.size(), 1u);
  EXPECT_EQ(p.cells[p.wave_indices[0]], r.entrances[0].a);
  EXPECT_THROW(partitionIntoBlocks(g, 1), std::invalid_argument);
}

TEST(WavePoints, UserWavePointsAreVisitedInOrder) {
  const PlanningGrid g = PlanningGrid::freeGrid(30, 30, 0.1);
  const WavePlan p = planThroughWavePoints(g, {0, 0}, {29, 0}, {{15, 20}, {20, 5}});
  ASSERT_TRUE(p.found());
  ASSERT_EQ(p.wave_indices.size(), 2u);
  EXPECT_EQ(p.cells[p.wave_indices[0]], (Cell{15, 20}));
  EXPECT_EQ(p.cells[p.wave_indices[1]], (Cell{20, 5}));
  PlanningGrid b = g;
  b.setBlocked({15, 20}, true);
  EXPECT_EQ(planThroughWavePoints(b, {0, 0}, {29, 0}, {{15, 20}}).status, PlanStatus::kGoalBlocked);
}

}  // namespace
}  // namespace irgs
