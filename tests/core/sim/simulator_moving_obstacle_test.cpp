// Scripted moving obstacles in the Simulator: seen by the sonars, solid to the body, and polite.
#include <gtest/gtest.h>

#include "core/sim/body_clearance.hpp"
#include "core/sim/simulator.hpp"
#include "sim_test_support.hpp"

namespace irgs {
namespace {

using test::exactConfig;
using test::forwardSonar;
using test::squareRobot;

MovingObstacle box(std::vector<Vec2> path, double speed) {
  MovingObstacle m;
  m.id = "box";
  m.polygon = {Vec2(-0.2, -0.2), Vec2(0.2, -0.2), Vec2(0.2, 0.2), Vec2(-0.2, 0.2)};
  m.path = std::move(path);
  m.speed_mps = speed;
  m.loop = false;
  return m;
}

// A box walking from x = 3 toward (and through, if it could) the robot at 0.5 m/s.
WorldMap approaching() {
  WorldMap w;
  w.moving_obstacles.push_back(box({Vec2(3.0, 0.0), Vec2(-1.0, 0.0)}, 0.5));
  return w;
}

TEST(SimulatorMovingObstacles, TheSonarSeesTheObstacleComeCloser) {
  RobotProfile robot = squareRobot();
  robot.sonars = {forwardSonar()};
  Simulator sim(approaching(), robot, exactConfig());
  double first = -1.0, last = -1.0;
  for (int i = 0; i < 300; ++i) {
    for (const SonarReading& r : sim.step().sonar) {
      ASSERT_TRUE(r.echo);
      if (first < 0.0)
        first = r.range_m;
      last = r.range_m;
    }
  }
  // Front face at x - 0.2, sonar at x = 0.1: the first reading (t = 0.1 s) is 2.65 m, and it
  // is 1.45 m closer at t = 3 s.
  EXPECT_NEAR(first, 2.65, 0.02);
  EXPECT_NEAR(last, 1.2, 0.06);
  ASSERT_EQ(sim.movingObstaclePolygons().size(), 1u);
  EXPECT_NEAR(sim.movingObstaclePolygons()[0][0].x(), 1.3, 0.01);
}

TEST(SimulatorMovingObstacles, TheBodyCannotDriveIntoAStandingObstacle) {
  WorldMap w;
  w.moving_obstacles.push_back(box({Vec2(1.0, 0.0)}, 0.5));  // one waypoint: stands
  Simulator sim(w, squareRobot(), exactConfig());
  sim.setCommand({0.3, 0.0});
  for (int i = 0; i < 600; ++i)
    sim.step();
  const double front = sim.truePose().x + 0.15;  // squareRobot: 0.3 m square
  EXPECT_LE(front, 0.8 + 1e-6);
  EXPECT_GT(front, 0.79);
  std::vector<Vec2> body;
  for (const Vec2& v : sim.profile().body_outline)
    body.push_back(sim.truePose().toWorld(v));
  EXPECT_LT(bodyClearance(sim.world(), body, 1.0), 0.01);
}

TEST(SimulatorMovingObstacles, AnObstacleWaitsInsteadOfWalkingIntoTheRobot) {
  Simulator sim(approaching(), squareRobot(), exactConfig());  // the robot stands still
  for (int i = 0; i < 1000; ++i)
    sim.step();
  // The box stopped 5 cm before the robot's front face (x = 0.15).
  EXPECT_NEAR(sim.movingObstaclePolygons()[0][0].x(), 0.2, 0.01);
  std::vector<Vec2> body;
  for (const Vec2& v : sim.profile().body_outline)
    body.push_back(sim.truePose().toWorld(v));
  EXPECT_GT(bodyClearance(sim.world(), body, 1.0), 0.04);
}

}  // namespace
}  // namespace irgs
