#include "core/estimation/stereo_sonar.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "core/sim/random.hpp"

namespace irgs {
namespace {

constexpr double kS = 0.2;

TEST(StereoSonar, ReceiversSitRightAndLeftOfTheTransmitter) {
  const Pose2 sensor{1.0, 2.0, kPi / 2};  // boresight +y: right is +x
  EXPECT_NEAR(receiver1Position(sensor, kS).x(), 1.2, 1e-12);
  EXPECT_NEAR(receiver1Position(sensor, kS).y(), 2.0, 1e-12);
  EXPECT_NEAR(receiver2Position(sensor, kS).x(), 0.8, 1e-12);
}

TEST(StereoSonar, MirrorImageEchoesEqualTheClosedFormOfEquations3And4) {
  SimRandom rng(7);
  for (int i = 0; i < 200; ++i) {
    const double d = 0.3 + 3.0 * rng.uniform();
    const double theta = degToRad(-60.0 + 120.0 * rng.uniform());
    const double phi_t = 2.0 * kPi * rng.uniform();
    // A wall whose normal (from the sensor) points along phi_t + theta, d ahead.
    const Pose2 sensor{-1.0 + 2.0 * rng.uniform(), -1.0 + 2.0 * rng.uniform(), wrapAngle(phi_t)};
    const double phi = wrapAngle(phi_t + theta);
    const Vec2 foot = sensor.position() + d * Vec2(std::cos(phi), std::sin(phi));
    const Vec2 along(-std::sin(phi), std::cos(phi));
    const WallLine wall = wallLineFacing({foot - along, foot + along}, sensor.position());
    const EchoPaths world = wallEchoPaths(wall, sensor, kS);
    const EchoPaths local = wallEchoPathsLocal(d, theta, kS);
    EXPECT_NEAR(world.r1_m, local.r1_m, 1e-9);
    EXPECT_NEAR(world.r2_m, local.r2_m, 1e-9);
  }
}

TEST(StereoSonar, NoiseFreeWallEchoesInvertExactlyAtManyPoses) {
  SimRandom rng(11);
  for (int i = 0; i < 500; ++i) {
    const double d = 0.2 + 4.8 * rng.uniform();
    const double theta = degToRad(-80.0 + 160.0 * rng.uniform());
    const Pose2 sensor{10.0 * rng.uniform() - 5.0, 10.0 * rng.uniform() - 5.0,
                       wrapAngle(6.0 * rng.uniform())};
    const double phi = wrapAngle(sensor.theta + theta);
    const Vec2 foot = sensor.position() + d * Vec2(std::cos(phi), std::sin(phi));
    const Vec2 along(-std::sin(phi), std::cos(phi));
    const WallLine wall = wallLineFacing({foot - along, foot + along}, sensor.position());
    const EchoPaths paths = wallEchoPaths(wall, sensor, kS);
    const StereoInversion inv = invertSpecular(paths.r1_m, paths.r2_m, kS);
    ASSERT_TRUE(inv.ok()) << toString(inv.status);
    EXPECT_NEAR(inv.d_m, d, 1e-9);
    EXPECT_NEAR(inv.theta_rad, theta, 1e-8);
  }
}

TEST(StereoSonar, NoiseFreeCornerEchoesInvertExactlyToDistanceAndBearingOfTheCorner) {
  SimRandom rng(12);
  for (int i = 0; i < 500; ++i) {
    const Pose2 sensor{4.0 * rng.uniform() - 2.0, 4.0 * rng.uniform() - 2.0,
                       wrapAngle(6.0 * rng.uniform())};
    const double d = 0.3 + 4.0 * rng.uniform();
    const double bearing = degToRad(-70.0 + 140.0 * rng.uniform());
    const double dir = sensor.theta + bearing;
    const Vec2 corner = sensor.position() + d * Vec2(std::cos(dir), std::sin(dir));
    const EchoPaths paths = cornerEchoPaths(corner, sensor, kS);
    const StereoInversion inv = invertSpecular(paths.r1_m, paths.r2_m, kS);
    ASSERT_TRUE(inv.ok());
    EXPECT_NEAR(inv.d_m, d, 1e-9);
    EXPECT_NEAR(inv.theta_rad, bearing, 1e-8);
  }
}

TEST(StereoSonar, EdgeInverseRecoversDiffractionEchoesExactly) {
  SimRandom rng(13);
  for (int i = 0; i < 500; ++i) {
    const Pose2 sensor{0.0, 0.0, wrapAngle(6.0 * rng.uniform())};
    const double d = 0.3 + 4.0 * rng.uniform();
    const double bearing = degToRad(-70.0 + 140.0 * rng.uniform());
    const double dir = sensor.theta + bearing;
    const Vec2 edge = d * Vec2(std::cos(dir), std::sin(dir));
    const EchoPaths paths = edgeEchoPaths(edge, sensor, kS);
    const StereoInversion inv = invertEdge(paths.r1_m, paths.r2_m, kS);
    ASSERT_TRUE(inv.ok());
    EXPECT_NEAR(inv.d_m, d, 1e-9);
    EXPECT_NEAR(inv.theta_rad, bearing, 1e-8);
    // The specular inverse (5) is only approximate for an edge.
    const StereoInversion spec = invertSpecular(paths.r1_m, paths.r2_m, kS);
    ASSERT_TRUE(spec.ok());
    EXPECT_NEAR(spec.d_m, d, 0.05);
  }
}

TEST(StereoSonar, BearingSignFollowsEquations7And8) {
  // (7): r1 > r2 -> theta > 0 (wall normal left of the boresight, R1 on the right is farther).
  EXPECT_GT(invertSpecular(2.1, 2.0, kS).theta_rad, 0.0);
  // (8): r1 < r2 -> theta < 0.
  EXPECT_LT(invertSpecular(2.0, 2.1, kS).theta_rad, 0.0);
  EXPECT_EQ(invertSpecular(2.0, 2.0, kS).theta_rad, 0.0);
  // Geometric check: a wall ahead-left (normal at +30 deg) gives r1 > r2.
  const EchoPaths p = wallEchoPathsLocal(1.0, degToRad(30.0), kS);
  EXPECT_GT(p.r1_m, p.r2_m);
}

TEST(StereoSonar, ValidityChecksRejectImpossibleEchoes) {
  // (5) radicand (r1^2 + r2^2)/2 - s^2 <= 0.
  EXPECT_EQ(invertSpecular(0.1, 0.1, kS).status, InversionStatus::kNegativeRadicand);
  EXPECT_EQ(invertSpecular(0.2, 0.2, kS).status, InversionStatus::kNegativeRadicand);
  // (6) |(r1^2 - r2^2)/(8 s d)| >= 1: path difference larger than the baseline allows.
  EXPECT_EQ(invertSpecular(2.0, 1.0, kS).status, InversionStatus::kBearingOutOfRange);
  EXPECT_EQ(invertEdge(2.0, 1.0, kS).status, InversionStatus::kBearingOutOfRange);
  // Non-finite and non-positive inputs.
  EXPECT_EQ(invertSpecular(std::nan(""), 1.0, kS).status, InversionStatus::kNonFinite);
  EXPECT_EQ(invertSpecular(1.0, INFINITY, kS).status, InversionStatus::kNonFinite);
  EXPECT_EQ(invertSpecular(-1.0, 1.0, kS).status, InversionStatus::kNonFinite);
  EXPECT_EQ(invertSpecular(1.0, 1.0, 0.0).status, InversionStatus::kNonFinite);
  EXPECT_EQ(invertEdge(1.0, 1.0, -0.2).status, InversionStatus::kNonFinite);
  EXPECT_FALSE(invertSpecular(1.0, 1.0, 0.0).ok());
}

TEST(StereoSonar, TofConvertsWithTheConfiguredSpeedOfSoundAndGatesAt12ms) {
  EXPECT_NEAR(tofToPathLength(0.012, 343.0), 4.116, 1e-12);
  EXPECT_NEAR(pathLengthToTof(4.116, 343.0), 0.012, 1e-15);
  EXPECT_NEAR(tofToPathLength(0.012, 333.0), 3.996, 1e-12);
  const StereoSonarParams params;  // 12 ms, 343 m/s
  EXPECT_TRUE(withinMaxTof({4.0, 4.1}, params));
  EXPECT_FALSE(withinMaxTof({4.0, 4.2}, params));
  EXPECT_FALSE(withinMaxTof({std::nan(""), 1.0}, params));
  StereoSonarParams bad;
  bad.speed_of_sound_mps = 0.0;
  EXPECT_THROW(validate(bad), std::invalid_argument);
  bad = {};
  bad.half_baseline_m = std::nan("");
  EXPECT_THROW(validate(bad), std::invalid_argument);
}

}  // namespace
}  // namespace irgs
