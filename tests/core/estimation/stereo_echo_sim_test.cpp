#include "core/estimation/stereo_echo_sim.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace irgs {
namespace {

WorldMap mapWithWalls(std::vector<std::vector<Vec2>> polylines) {
  WorldMap map;
  int i = 0;
  for (auto& pts : polylines)
    map.walls.push_back({"w" + std::to_string(i++), std::move(pts), false, {}});
  return map;
}

StereoEchoNoise noiseless() {
  StereoEchoNoise n;
  n.path_stddev_m = 0.0;
  n.path_stddev_per_m = 0.0;
  return n;
}

TEST(StereoEchoSim, WallAheadGivesTheSpecularEchoThatInvertsToItsDistanceAndBearing) {
  const WorldMap map = mapWithWalls({{{2.0, -3.0}, {2.0, 3.0}}});
  const StereoEchoSimulator sim(map, {}, noiseless());
  const Pose2 sensor{0.5, 0.2, degToRad(10.0)};
  const SimulatedEcho e = sim.idealEcho(sensor);
  ASSERT_EQ(e.status, EchoStatus::kEcho);
  EXPECT_EQ(e.kind, ReflectorKind::kWall);
  EXPECT_EQ(e.reflector_id, "w0");
  const StereoInversion inv = invertSpecular(e.paths.r1_m, e.paths.r2_m, 0.2);
  ASSERT_TRUE(inv.ok());
  EXPECT_NEAR(inv.d_m, 1.5, 1e-9);
  EXPECT_NEAR(inv.theta_rad, degToRad(-10.0), 1e-9);  // the normal is right of the boresight
}

TEST(StereoEchoSim, ReflectionPointsOffTheSegmentGiveNoEcho) {
  // Short wall piece well to the side of the specular point.
  const WorldMap map = mapWithWalls({{{2.0, 1.0}, {2.0, 3.0}}});
  const StereoEchoSimulator sim(map, {}, noiseless());
  EXPECT_EQ(sim.idealEcho({0.0, 0.0, 0.0}).status, EchoStatus::kNoReflector);
}

TEST(StereoEchoSim, NearestReflectorWinsAndOccludedWallsAreSilent) {
  const WorldMap map = mapWithWalls({{{3.0, -3.0}, {3.0, 3.0}}, {{1.0, -3.0}, {1.0, 3.0}}});
  const StereoEchoSimulator sim(map, {}, noiseless());
  const SimulatedEcho e = sim.idealEcho({0.0, 0.0, 0.0});
  ASSERT_EQ(e.status, EchoStatus::kEcho);
  EXPECT_EQ(e.reflector_id, "w1");
  // From between the walls looking at the far one: the near wall is behind, the far wall echoes.
  EXPECT_EQ(sim.idealEcho({2.0, 0.0, 0.0}).reflector_id, "w0");
}

TEST(StereoEchoSim, CornerSeenDiagonallyRetroReflects) {
  // Concave corner at (2, 2) between walls along x and y; sensor looking at it at 45 deg, so both
  // walls are outside the 30 deg beam and the corner is the first echo.
  WorldMap map = mapWithWalls({{{-3.0, 2.0}, {2.0, 2.0}, {2.0, -3.0}}});
  map.features.push_back({"C", PointFeatureKind::kCorner, {2.0, 2.0}, {}});
  const StereoEchoSimulator sim(map, {}, noiseless());
  const SimulatedEcho e = sim.idealEcho({1.0, 1.0, kPi / 4});
  ASSERT_EQ(e.status, EchoStatus::kEcho);
  EXPECT_EQ(e.kind, ReflectorKind::kCorner);
  const StereoInversion inv = invertSpecular(e.paths.r1_m, e.paths.r2_m, 0.2);
  ASSERT_TRUE(inv.ok());
  EXPECT_NEAR(inv.d_m, std::sqrt(2.0), 1e-9);
  EXPECT_NEAR(inv.theta_rad, 0.0, 1e-9);
  // From outside the corner's opening it does not retro-reflect.
  EXPECT_NE(sim.idealEcho({3.0, 3.0, -3 * kPi / 4}).kind, ReflectorKind::kCorner);
}

TEST(StereoEchoSim, EdgeDiffractsAndTheEdgeInverseRecoversIt) {
  // Convex edge at (2, 0): end of a wall running away along +x... seen head-on along its line.
  WorldMap map = mapWithWalls({{{2.0, 0.0}, {6.0, 0.0}}});
  map.features.push_back({"E", PointFeatureKind::kEdge, {2.0, 0.0}, {}});
  const StereoEchoSimulator sim(map, {}, noiseless());
  const SimulatedEcho e = sim.idealEcho({0.5, 0.3, 0.0});
  ASSERT_EQ(e.status, EchoStatus::kEcho);
  EXPECT_EQ(e.kind, ReflectorKind::kEdge);
  const StereoInversion inv = invertEdge(e.paths.r1_m, e.paths.r2_m, 0.2);
  ASSERT_TRUE(inv.ok());
  EXPECT_NEAR(inv.d_m, std::hypot(1.5, 0.3), 1e-9);
  EXPECT_NEAR(inv.theta_rad, std::atan2(-0.3, 1.5), 1e-9);
}

TEST(StereoEchoSim, EchoesBeyondTheMaxTofAreGated) {
  const WorldMap map = mapWithWalls({{{2.2, -5.0}, {2.2, 5.0}}});
  const StereoEchoSimulator sim(map, {}, noiseless());  // 12 ms at 343 m/s: d about 2.06 m
  EXPECT_EQ(sim.idealEcho({0.0, 0.0, 0.0}).status, EchoStatus::kBeyondMaxTof);
  EXPECT_EQ(sim.idealEcho({0.3, 0.0, 0.0}).status, EchoStatus::kEcho);
  StereoSonarParams slow;
  slow.max_tof_s = 0.015;
  const StereoEchoSimulator sim15(map, slow, noiseless());
  EXPECT_EQ(sim15.idealEcho({0.0, 0.0, 0.0}).status, EchoStatus::kEcho);
}

TEST(StereoEchoSim, NoiseAndDropoutsAreSeededAndDeterministic) {
  const WorldMap map = mapWithWalls({{{1.5, -5.0}, {1.5, 5.0}}});
  StereoEchoNoise noise;
  noise.path_stddev_m = 0.003;
  noise.dropout_probability = 0.2;
  const StereoEchoSimulator sim(map, {}, noise);
  SimRandom a(42), b(42), c(43);
  int dropouts = 0, differs = 0;
  double sum_err = 0.0, sum_sq = 0.0;
  const int n = 2000;
  for (int i = 0; i < n; ++i) {
    const SimulatedEcho ea = sim.echo({0.0, 0.0, 0.0}, a);
    const SimulatedEcho eb = sim.echo({0.0, 0.0, 0.0}, b);
    const SimulatedEcho ec = sim.echo({0.0, 0.0, 0.0}, c);
    ASSERT_EQ(ea.status, eb.status);
    ASSERT_EQ(ea.paths.r1_m, eb.paths.r1_m);
    if (ea.status == EchoStatus::kDropout) {
      ++dropouts;
      continue;
    }
    ASSERT_EQ(ea.status, EchoStatus::kEcho);
    if (ec.status == EchoStatus::kEcho && ec.paths.r1_m != ea.paths.r1_m)
      ++differs;
    const double err = ea.paths.r1_m - ea.true_paths.r1_m;
    sum_err += err;
    sum_sq += err * err;
  }
  EXPECT_NEAR(static_cast<double>(dropouts) / n, 0.2, 0.03);
  EXPECT_GT(differs, n / 2);
  const double kept = n - dropouts;
  const double expected_sd = 0.003 + 0.001 * 3.0;  // r about 3 m
  EXPECT_NEAR(sum_err / kept, 0.0, 0.001);
  EXPECT_NEAR(std::sqrt(sum_sq / kept), expected_sd, 0.1 * expected_sd);
}

TEST(StereoEchoSim, BadConfigurationAndPosesThrow) {
  const WorldMap map = mapWithWalls({{{1.5, -5.0}, {1.5, 5.0}}});
  StereoEchoNoise noise;
  noise.dropout_probability = 1.5;
  EXPECT_THROW(StereoEchoSimulator(map, {}, noise), std::invalid_argument);
  noise = {};
  noise.path_stddev_m = -1.0;
  EXPECT_THROW(StereoEchoSimulator(map, {}, noise), std::invalid_argument);
  const StereoEchoSimulator sim(map, {}, {});
  SimRandom rng(1);
  EXPECT_THROW(sim.echo({std::nan(""), 0.0, 0.0}, rng), std::invalid_argument);
}

TEST(StereoEchoSim, DefaultNoiseKeepsDistanceErrorsUnderOneCentimetreWithinTwoMetres) {
  // Digest 1.10 (Fig. 8/9): d error < 1 cm within 2 m; bearing within a few degrees at 1 m and
  // +/-20 deg.
  const WorldMap map = mapWithWalls({{{0.0, -10.0}, {0.0, 10.0}}});
  const StereoEchoSimulator sim(map, {}, {});
  SimRandom rng(99);
  for (double d : {0.5, 1.0, 1.5, 2.0}) {
    for (double deg : {-20.0, 0.0, 20.0}) {
      const Pose2 sensor{-d, 0.0, degToRad(-deg)};  // wall normal at +deg from the boresight
      double sq_d = 0.0, sq_t = 0.0;
      int n = 0;
      for (int i = 0; i < 400; ++i) {
        const SimulatedEcho e = sim.echo(sensor, rng);
        if (e.status != EchoStatus::kEcho)
          continue;
        const StereoInversion inv = invertSpecular(e.paths.r1_m, e.paths.r2_m, 0.2);
        ASSERT_TRUE(inv.ok());
        sq_d += (inv.d_m - d) * (inv.d_m - d);
        sq_t += (inv.theta_rad - degToRad(deg)) * (inv.theta_rad - degToRad(deg));
        ++n;
      }
      ASSERT_GT(n, 300);
      EXPECT_LT(std::sqrt(sq_d / n), 0.01) << "d " << d << " angle " << deg;
      EXPECT_LT(std::sqrt(sq_t / n), degToRad(3.0)) << "d " << d << " angle " << deg;
    }
  }
}

}  // namespace
}  // namespace irgs
