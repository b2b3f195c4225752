#include "core/sim/ray_caster.hpp"

#include <gtest/gtest.h>

#include <random>

#include "core/sim/random.hpp"

namespace irgs {
namespace {

Vec2 unit(double angle) {
  return {std::cos(angle), std::sin(angle)};
}

TEST(NaiveSegmentCaster, FindsTheNearestSegmentAndANormalFacingTheRay) {
  const std::vector<Segment> segments = {{{3, -1}, {3, 1}}, {{2, -1}, {2, 1}}, {{5, -1}, {5, 1}}};
  const NaiveSegmentCaster caster(segments);
  const auto hit = caster.cast({0, 0}, {1, 0}, 10.0);
  ASSERT_TRUE(hit);
  EXPECT_DOUBLE_EQ(hit->distance_m, 2.0);
  EXPECT_EQ(hit->normal, Vec2(-1, 0));
  const auto back = caster.cast({4, 0}, {-1, 0}, 10.0);
  ASSERT_TRUE(back);
  EXPECT_DOUBLE_EQ(back->distance_m, 1.0);
  EXPECT_EQ(back->normal, Vec2(1, 0));
}

TEST(NaiveSegmentCaster, RespectsMaxRangeAndMissesBehindAndBeside) {
  const std::vector<Segment> segments = {{{2, -1}, {2, 1}}};
  const NaiveSegmentCaster caster(segments);
  EXPECT_FALSE(caster.cast({0, 0}, {1, 0}, 1.5));
  EXPECT_TRUE(caster.cast({0, 0}, {1, 0}, 2.0));
  EXPECT_FALSE(caster.cast({0, 0}, {-1, 0}, 10.0));
  EXPECT_FALSE(caster.cast({0, 2}, {1, 0}, 10.0));
  EXPECT_FALSE(caster.cast({0, 0}, {0, 1}, 10.0));  // parallel
}

TEST(NaiveSegmentCaster, BreaksAnExactTieTowardsTheLowerIndex) {
  // Two segments meeting at (2, 0): the ray hits both at exactly 2.
  const std::vector<Segment> segments = {{{2, 0}, {3, 1}}, {{2, 0}, {3, -1}}};
  const NaiveSegmentCaster caster(segments);
  const auto hit = caster.cast({0, 0}, {1, 0}, 10.0);
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->distance_m, 2.0);
  EXPECT_EQ(hit->normal, PreparedSegments(segments).normalFacing(0, {1, 0}));
}

// Random scenes: short and long, axis-aligned and slanted segments, polylines sharing
// endpoints, rays from inside and outside the grid.
std::vector<Segment> randomScene(SimRandom& rng, int count) {
  std::vector<Segment> out;
  Vec2 chain = Vec2::Zero();
  for (int i = 0; i < count; ++i) {
    const Vec2 a(20.0 * rng.uniform() - 10.0, 20.0 * rng.uniform() - 10.0);
    const double kind = rng.uniform();
    const double length = kind < 0.1 ? 15.0 * rng.uniform() : 2.0 * rng.uniform();
    Vec2 d = unit(2.0 * kPi * rng.uniform());
    if (kind > 0.6)  // axis-aligned, like most indoor walls
      d = rng.uniform() < 0.5 ? Vec2(1, 0) : Vec2(0, 1);
    if (kind > 0.85 && i > 0) {  // continue a polyline from the previous end
      out.push_back({chain, chain + length * d});
    } else {
      out.push_back({a, a + length * d});
    }
    chain = out.back().b;
  }
  return out;
}

void expectSameHit(const std::optional<RayHit>& a, const std::optional<RayHit>& b,
                   const std::string& what) {
  ASSERT_EQ(a.has_value(), b.has_value()) << what;
  if (a) {
    EXPECT_EQ(a->distance_m, b->distance_m) << what;  // bit-identical, not just close
    EXPECT_EQ(a->normal, b->normal) << what;
  }
}

TEST(GridSegmentCaster, AgreesExactlyWithTheNaiveCasterOnRandomScenes) {
  SimRandom rng(2024);
  int hits = 0;
  for (int scene = 0; scene < 12; ++scene) {
    const auto segments = randomScene(rng, 50 + 40 * scene);
    const NaiveSegmentCaster naive(segments);
    for (const double cell : {0.0, 0.13, 0.5, 3.0}) {
      const GridSegmentCaster grid(segments, cell);
      for (int ray = 0; ray < 400; ++ray) {
        const Vec2 origin(30.0 * rng.uniform() - 15.0, 30.0 * rng.uniform() - 15.0);
        const Vec2 dir = unit(2.0 * kPi * rng.uniform());
        const double range = rng.uniform() < 0.1 ? 100.0 : 6.0 * rng.uniform();
        const auto expected = naive.cast(origin, dir, range);
        hits += expected.has_value();
        expectSameHit(grid.cast(origin, dir, range), expected, "cast");

        // A sonar-like fan from the same origin.
        std::vector<Vec2> dirs;
        const double centre = 2.0 * kPi * rng.uniform();
        for (int k = 0; k < 11; ++k)
          dirs.push_back(unit(centre + degToRad(30.0) * (k / 10.0 - 0.5)));
        std::vector<std::optional<RayHit>> fan(dirs.size());
        grid.castFan(origin, dirs, range, fan);
        for (std::size_t k = 0; k < dirs.size(); ++k)
          expectSameHit(fan[k], naive.cast(origin, dirs[k], range), "fan");
      }
    }
  }
  EXPECT_GT(hits, 2000);  // the scenes really are hit, not mostly missed
}

TEST(GridSegmentCaster, AgreesWithTheNaiveCasterOnRaysAlongGridLinesAndThroughVertices) {
  // A lattice of unit walls on the grid lines; rays along lines and through lattice points
  // are where cell-border rounding would show.
  std::vector<Segment> segments;
  for (int i = -3; i <= 3; ++i) {
    segments.push_back({{static_cast<double>(i), -3.0}, {static_cast<double>(i), -2.0}});
    segments.push_back({{-3.0, static_cast<double>(i)}, {-2.0, static_cast<double>(i)}});
    segments.push_back({{static_cast<double>(i), static_cast<double>(i)},
                        {static_cast<double>(i) + 0.5, static_cast<double>(i) + 0.5}});
  }
  const NaiveSegmentCaster naive(segments);
  const GridSegmentCaster grid(segments, 0.5);
  for (int ox = -4; ox <= 4; ++ox) {
    for (int oy = -4; oy <= 4; ++oy) {
      for (int a = 0; a < 16; ++a) {
        const Vec2 origin(0.5 * ox, 0.5 * oy);
        const Vec2 dir = unit(a * kPi / 8.0);
        expectSameHit(grid.cast(origin, dir, 20.0), naive.cast(origin, dir, 20.0), "lattice");
      }
    }
  }
}

TEST(GridSegmentCaster, HandlesAnEmptyWorldAndRaysFromFarOutside) {
  const GridSegmentCaster empty(std::vector<Segment>{});
  EXPECT_FALSE(empty.cast({0, 0}, {1, 0}, 10.0));
  const std::vector<Segment> segments = {{{0, -1}, {0, 1}}};
  const GridSegmentCaster grid(segments);
  const auto hit = grid.cast({-1000, 0}, {1, 0}, 2000.0);
  ASSERT_TRUE(hit);
  EXPECT_DOUBLE_EQ(hit->distance_m, 1000.0);
  EXPECT_FALSE(grid.cast({-1000, 0}, {1, 0}, 999.0));
  EXPECT_FALSE(grid.cast({-1000, 5}, {1, 0}, 2000.0));
}

}  // namespace
}  // namespace irgs
