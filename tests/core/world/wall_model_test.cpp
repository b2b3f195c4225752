#include "core/world/wall_model.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>

namespace irgs {
namespace {

constexpr double kTol = 1e-12;

void expectLine(const WallLine& w, double p_r, double phi, int p_v) {
  EXPECT_NEAR(w.p_r_m, p_r, kTol);
  EXPECT_NEAR(wrapAngle(w.phi_rad - phi), 0.0, kTol) << "phi " << w.phi_rad << " vs " << phi;
  EXPECT_EQ(w.p_v, p_v);
}

TEST(WallModel, FaceTowardsTheOriginIsVisible) {
  // Wall on x = 1, its face looking back at the origin.
  const WallLine w = wallLineFromFace({{1, -1}, {1, 1}}, {-1, 0});
  expectLine(w, 1.0, 0.0, +1);
  const Pose2 sensor{0.2, 0.3, 0.1};
  EXPECT_NEAR(predictedWallDistance(w, sensor), 0.8, kTol);  // 1 - 0.2
  EXPECT_NEAR(predictedWallBearing(w, sensor), -0.1, kTol);  // phi - heading
  const FacingLine f = robotFacing(w);
  EXPECT_NEAR(f.phi_eff_rad, 0.0, kTol);
  EXPECT_NEAR(f.p_eff_m, 1.0, kTol);
}

TEST(WallModel, FaceAwayFromTheOriginHasNegativeVisibilityAndFlipsInRobotFacingForm) {
  const WallLine w = wallLineFromFace({{1, -1}, {1, 1}}, {+1, 0});
  expectLine(w, 1.0, 0.0, -1);
  const FacingLine f = robotFacing(w);  // A000-9: phi + pi, -P_R
  EXPECT_NEAR(std::abs(f.phi_eff_rad), kPi, kTol);
  EXPECT_NEAR(f.p_eff_m, -1.0, kTol);
  // A sensor at x = 2.5 looking towards -x sees the face 1.5 m ahead, straight on.
  const Pose2 sensor{2.5, 0.0, kPi};
  EXPECT_NEAR(predictedWallDistance(w, sensor), 1.5, kTol);  // (17): -1 * (1 - 2.5)
  EXPECT_NEAR(predictedWallBearing(w, sensor), 0.0, kTol);
  // Without A000-9 the bearing (16) would be off by pi:
  EXPECT_NEAR(std::abs(wrapAngle(w.phi_rad - sensor.theta)), kPi, kTol);
}

TEST(WallModel, DiagonalWallByHand) {
  // x + y = 2: foot of the perpendicular (1, 1), P_R = sqrt(2), phi = 45 deg.
  const WallLine w = wallLineFromFace({{2, 0}, {0, 2}}, {-1, -1});
  expectLine(w, std::sqrt(2.0), kPi / 4, +1);
  EXPECT_NEAR(predictedWallDistance(w, {0, 0, 0}), std::sqrt(2.0), kTol);
  EXPECT_NEAR(predictedWallBearing(w, {0, 0, 0}), kPi / 4, kTol);
  // From (1, 0) heading +y: distance sqrt(2) - 1/sqrt(2) = 1/sqrt(2), normal 45 deg to the right.
  EXPECT_NEAR(predictedWallDistance(w, {1, 0, kPi / 2}), 1.0 / std::sqrt(2.0), kTol);
  EXPECT_NEAR(predictedWallBearing(w, {1, 0, kPi / 2}), -kPi / 4, kTol);
}

TEST(WallModel, WallBelowTheOriginPointsDown) {
  // y = -2 facing the origin: phi = 270 deg (-90 deg after wrapping), as in Table 1's W3.
  const WallLine w = wallLineFromFace({{-1, -2}, {3, -2}}, {0, 1});
  expectLine(w, 2.0, degToRad(270.0), +1);
  EXPECT_NEAR(w.phi_rad, -kPi / 2, kTol);
}

TEST(WallModel, LineThroughTheOriginIsVisibleAndPointsAgainstTheFaceNormal) {
  // Table 1's W0 (P_R 0, phi 0, P_V +1) is the line x = 0 with its face looking towards -x.
  expectLine(wallLineFromFace({{0, -1}, {0, 1}}, {-1, 0}), 0.0, 0.0, +1);
  expectLine(wallLineFromFace({{0, -1}, {0, 1}}, {+1, 0}), 0.0, kPi, +1);
  // Distance stays positive in front of either face.
  EXPECT_NEAR(predictedWallDistance(wallLineFromFace({{0, -1}, {0, 1}}, {+1, 0}), {0.7, 5, 0}), 0.7,
              kTol);
}

TEST(WallModel, OnlyThePerpendicularPartOfTheFaceNormalMatters) {
  expectLine(wallLineFromFace({{1, -1}, {1, 1}}, {-0.1, 50.0}), 1.0, 0.0, +1);
}

TEST(WallModel, FacingPointAndBothFacesAgreeWithExplicitNormals) {
  const Segment s{{1, -1}, {1, 1}};
  expectLine(wallLineFacing(s, {3, 0}), 1.0, 0.0, -1);
  expectLine(wallLineFacing(s, {-3, 7}), 1.0, 0.0, +1);
  const auto faces = wallLineFaces(s);  // a -> b runs along +y: left is -x
  expectLine(faces[0], 1.0, 0.0, +1);
  expectLine(faces[1], 1.0, 0.0, -1);
}

TEST(WallModel, PredictionsMatchDirectGeometryForRandomWallsAndSensors) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> coord(-10.0, 10.0);
  std::uniform_real_distribution<double> angle(-kPi, kPi);
  for (int i = 0; i < 2000; ++i) {
    const Segment s{{coord(rng), coord(rng)}, {coord(rng), coord(rng)}};
    if (s.length() < 1e-3)
      continue;
    const Pose2 sensor{coord(rng), coord(rng), angle(rng)};
    const double side = cross(s.b - s.a, sensor.position() - s.a);
    if (std::abs(side) < 1e-6)
      continue;
    const WallLine w = wallLineFacing(s, sensor.position());
    // Foot of the perpendicular from the sensor onto the infinite line.
    const Vec2 d = s.direction();
    const Vec2 foot = s.a + d * (sensor.position() - s.a).dot(d);
    const Vec2 to_foot = foot - sensor.position();
    EXPECT_NEAR(predictedWallDistance(w, sensor), to_foot.norm(), 1e-9);
    EXPECT_NEAR(predictedWallBearing(w, sensor),
                wrapAngle(std::atan2(to_foot.y(), to_foot.x()) - sensor.theta), 1e-9);
    // P_V: is the origin on the same side as the sensor?
    const double origin_side = cross(s.b - s.a, -s.a);
    if (std::abs(origin_side) > 1e-6) {
      EXPECT_EQ(w.p_v, (origin_side > 0) == (side > 0) ? 1 : -1);
    }
    // The line equation holds at both end points.
    EXPECT_NEAR(s.a.x() * std::cos(w.phi_rad) + s.a.y() * std::sin(w.phi_rad), w.p_r_m, 1e-9);
    EXPECT_NEAR(s.b.x() * std::cos(w.phi_rad) + s.b.y() * std::sin(w.phi_rad), w.p_r_m, 1e-9);
    EXPECT_GE(w.p_r_m, 0.0);
  }
}

TEST(WallModel, CornerAndEdgePredictions) {
  // (18)/(19)
  EXPECT_NEAR(predictedPointDistance({3, 4}, {0, 0, 1.0}), 5.0, kTol);
  EXPECT_NEAR(predictedPointBearing({0, 2}, {0, 0, kPi / 2}), 0.0, kTol);
  EXPECT_NEAR(predictedPointBearing({-1, 0}, {0, 0, 0.5}), wrapAngle(kPi - 0.5), kTol);
}

TEST(WallModel, MisuseThrows) {
  EXPECT_THROW(wallLineFromFace({{1, 1}, {1, 1}}, {1, 0}), std::invalid_argument);
  EXPECT_THROW(wallLineFromFace({{0, 0}, {1, 0}}, {1, 0}), std::invalid_argument);
  EXPECT_THROW(wallLineFacing({{0, 0}, {1, 0}}, {5, 0}), std::invalid_argument);
}

}  // namespace
}  // namespace irgs
