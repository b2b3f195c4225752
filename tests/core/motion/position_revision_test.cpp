#include "core/motion/position_revision.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "core/geometry/types.hpp"

namespace irgs {
namespace {

constexpr double kQ = degToRad(15.0);

TEST(PositionRevision, QuantiseRoundsToTheNearestQuantum) {
  EXPECT_DOUBLE_EQ(quantiseAngle(degToRad(22.0), kQ), degToRad(15.0));
  EXPECT_DOUBLE_EQ(quantiseAngle(degToRad(23.0), kQ), degToRad(30.0));
  EXPECT_DOUBLE_EQ(quantiseAngle(degToRad(-98.0), kQ), degToRad(-105.0));
  EXPECT_DOUBLE_EQ(quantiseAngle(0.3, 0.0), 0.3);
}

TEST(PositionRevision, FrontWallSquareOnAsksForAQuarterTurnAwayFromTheWallSide) {
  // (a) both front sonars read the same: the wall is perpendicular to the heading.
  EXPECT_NEAR(*frontWallTurn(0.4, 0.4, 0.29, /*wall_on_left=*/true, kQ), degToRad(-90.0), 1e-12);
  EXPECT_NEAR(*frontWallTurn(0.4, 0.4, 0.29, /*wall_on_left=*/false, kQ), degToRad(90.0), 1e-12);
}

TEST(PositionRevision, FrontWallAt45DegreesGivesA45DegreeTurn) {
  // Wall ahead running at 45 deg: the right sonar is b farther than the left one.
  const double b = 0.29;
  const double turn = *frontWallTurn(0.3, 0.3 + b, b, /*wall_on_left=*/true, kQ);
  EXPECT_NEAR(turn, degToRad(-45.0), 1e-12);
  // Slightly noisy readings still land on the quantum.
  EXPECT_NEAR(*frontWallTurn(0.31, 0.3 + b, b, true, kQ), degToRad(-45.0), 1e-12);
}

TEST(PositionRevision, FrontWallRejectsBadInput) {
  EXPECT_FALSE(frontWallTurn(0.3, 0.3, 0.0, true, kQ));
  EXPECT_FALSE(frontWallTurn(NAN, 0.3, 0.2, true, kQ));
  EXPECT_FALSE(frontWallTurn(-0.1, 0.3, 0.2, true, kQ));
}

TEST(PositionRevision, SideWallAngleFollowsTheRightTriangle) {
  // (c) wall on the left, front sonar reads b*tan(20 deg) more: the wall turns away CCW.
  const double b = 0.12;
  const double a = *sideWallAngle(0.3 + b * std::tan(degToRad(20.0)), 0.3, b, true);
  EXPECT_NEAR(a, degToRad(20.0), 1e-12);
  // Same readings on the right side: the wall turns clockwise.
  EXPECT_NEAR(*sideWallAngle(0.3 + b * std::tan(degToRad(20.0)), 0.3, b, false), degToRad(-20.0),
              1e-12);
}

TEST(PositionRevision, ParallelCorrectionHasA15DegreeDeadband) {
  EXPECT_FALSE(parallelCorrection(degToRad(14.0), kQ, kQ));
  EXPECT_NEAR(*parallelCorrection(degToRad(16.0), kQ, kQ), degToRad(15.0), 1e-12);
  EXPECT_NEAR(*parallelCorrection(degToRad(-38.0), kQ, kQ), degToRad(-45.0), 1e-12);
}

TEST(PositionRevision, CornerClearanceLeavesTheSetDistancePastTheCorner) {
  // (b) a sonar at x = 0.1 with a narrow beam: corner at 0.1 ahead, drive 0.1 + 0.3.
  EXPECT_NEAR(cornerClearance(0.1, 0.15, 0.0, 0.3), 0.4, 1e-12);
  // A wide beam loses the wall later: the corner is behind the sensor axis.
  EXPECT_NEAR(cornerClearance(0.1, 0.2, degToRad(12.5), 0.3),
              0.1 - 0.2 * std::tan(degToRad(12.5)) + 0.3, 1e-12);
  EXPECT_GE(cornerClearance(-1.0, 0.2, 0.2, 0.3), 0.0);
}

TEST(PositionRevision, DistanceKeepingSteersBackInsideTheValidDistance) {
  const double max = degToRad(30.0);
  EXPECT_NEAR(distanceKeepingOffset(0.3, 0.3, 1.0, 2.0, max), 0.0, 1e-12);
  EXPECT_NEAR(distanceKeepingOffset(0.35, 0.3, 1.0, 2.0, max), 0.1, 1e-12);
  EXPECT_NEAR(distanceKeepingOffset(0.2, 0.3, 1.0, 2.0, max), -0.2, 1e-12);
  EXPECT_NEAR(distanceKeepingOffset(0.9, 0.3, 1.0, 2.0, max), max, 1e-12);
  // (d) beyond the valid distance (or no reading) the full approach angle is used.
  EXPECT_NEAR(distanceKeepingOffset(1.5, 0.3, 1.0, 0.01, max), max, 1e-12);
  EXPECT_NEAR(distanceKeepingOffset(INFINITY, 0.3, 1.0, 2.0, max), max, 1e-12);
}

}  // namespace
}  // namespace irgs
