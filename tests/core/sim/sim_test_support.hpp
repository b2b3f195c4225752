#pragma once
// Worlds and robots built in code for the simulator tests (no files, no other engineers' code).

#include "core/robot/robot_profile.hpp"
#include "core/sim/simulator.hpp"
#include "core/world/world_map.hpp"

namespace irgs::test {

// A 0.3 m x 0.3 m square robot, wheel radius 0.05 m, wheelbase 0.3 m, 2700 ticks per wheel
// radian; limits 1 m/s, 2 rad/s, 0.8 m/s², 4 rad/s²; bumpers on the front (0) and rear (1)
// faces. No sensors unless a test adds them.
inline RobotProfile squareRobot() {
  RobotProfile p;
  p.name = "square";
  p.drive.wheel_radius_m = 0.05;
  p.drive.wheelbase_m = 0.3;
  p.limits.max_speed_mps = 1.0;
  p.limits.max_turn_rate_radps = 2.0;
  p.limits.max_accel_mps2 = 0.8;
  p.limits.max_turn_accel_radps2 = 4.0;
  p.body_outline = {{0.15, -0.15}, {0.15, 0.15}, {-0.15, 0.15}, {-0.15, -0.15}};
  BumperSpec front;
  front.name = "front";
  front.position = {0.15, 0.0};
  front.normal_rad = 0.0;
  front.half_width_m = 0.15;
  BumperSpec rear = front;
  rear.name = "rear";
  rear.position = {-0.15, 0.0};
  rear.normal_rad = kPi;
  p.bumpers = {front, rear};
  return p;
}

inline SonarSpec forwardSonar(double beam_deg = 10.0) {
  SonarSpec s;
  s.name = "front";
  s.mount = {0.1, 0.0, 0.0};
  s.beam_width_rad = degToRad(beam_deg);
  s.min_range_m = 0.05;
  s.max_range_m = 4.0;
  s.rate_hz = 10.0;
  return s;
}

// A noiseless configuration: exact sensors, perfect odometry, no dropouts.
inline SimConfig exactConfig() {
  SimConfig c;
  c.sonar.range_stddev_m = 0.0;
  c.sonar.range_stddev_per_m = 0.0;
  c.sonar.dropout_probability = 0.0;
  c.proximity_stddev_m = 0.0;
  return c;
}

inline Wall wall(Vec2 a, Vec2 b) {
  Wall w;
  w.points = {a, b};
  return w;
}

// An empty world with the robot at the origin facing +x.
inline WorldMap emptyWorld() {
  WorldMap m;
  m.name = "empty";
  return m;
}

// A closed square room [-half, half]² as one closed wall.
inline WorldMap squareRoom(double half) {
  WorldMap m;
  m.name = "room";
  Wall w;
  w.points = {{-half, -half}, {half, -half}, {half, half}, {-half, half}};
  w.closed = true;
  m.walls.push_back(w);
  return m;
}

}  // namespace irgs::test
