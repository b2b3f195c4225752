#include "core/navigation/avoidance.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace irgs {
namespace {

TEST(Avoidance, WeightFallsLinearlyToZeroAtTheInfluenceDistance) {
  AvoidanceParams p;
  p.influence_m = 1.0;
  EXPECT_DOUBLE_EQ(repulsionWeight(p, 0.0), 1.0);
  EXPECT_DOUBLE_EQ(repulsionWeight(p, 0.25), 0.75);
  EXPECT_DOUBLE_EQ(repulsionWeight(p, 1.0), 0.0);
  EXPECT_DOUBLE_EQ(repulsionWeight(p, 3.0), 0.0);
}

TEST(Avoidance, AnObstacleOnTheLeftPushesRightAndBack) {
  AvoidanceParams p;
  p.k_rep = 1.0;
  const std::vector<SonarRay> rays = {
      {Vec2(0.0, 1.0), 0.5}, {Vec2(1.0, 0.0), 4.0}, {Vec2(0.0, -1.0), 4.0}};
  const Vec2 rep = repulsiveSum(p, rays);
  EXPECT_NEAR(rep.x(), 0.0, 1e-12);
  EXPECT_NEAR(rep.y(), -0.5, 1e-12);  // negated sum (A002-8): away from the near wall
}

TEST(Avoidance, EqualWallsOnBothSidesCancel) {
  AvoidanceParams p;
  const std::vector<SonarRay> rays = {{Vec2(0.0, 1.0), 0.6}, {Vec2(0.0, -1.0), 0.6}};
  EXPECT_NEAR(repulsiveSum(p, rays).norm(), 0.0, 1e-12);
}

TEST(Avoidance, MoveVectorIsTheUnitTargetPlusTheRepulsion) {
  AvoidanceParams p;
  p.target_gain = 1.0;
  const Vec2 move = moveVector(p, Vec2(5.0, 0.0), Vec2(0.0, -0.5));
  EXPECT_NEAR(move.x(), 1.0, 1e-12);
  EXPECT_NEAR(move.y(), -0.5, 1e-12);
  EXPECT_NEAR(moveVector(p, Vec2::Zero(), Vec2(0.2, 0.0)).x(), 0.2, 1e-12);
}

}  // namespace
}  // namespace irgs
