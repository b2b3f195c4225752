#pragma once
// A headless scenario: a map, a robot, a drive script and a seed, run through the simulator with
// the live sonar grid. The same code path as the GUI (Simulator -> SonarMapper -> OccupancyGrid),
// without a window; irgs-sim and the golden scenario tests use it.

#include <cstdint>
#include <optional>
#include <vector>

#include "core/mapping/occupancy_grid.hpp"
#include "core/robot/robot_profile.hpp"
#include "core/sim/drive_script.hpp"
#include "core/sim/sim_presets.hpp"
#include "core/sim/simulator.hpp"
#include "core/world/world_map.hpp"

namespace irgs {

struct ScenarioSpec {
  WorldMap map;
  RobotProfile profile;
  std::optional<Pose2> start;  // default: the map's start pose
  DriveScript script;          // empty script: the robot stands still
  SimConfig sim;
  double duration_s = 60.0;
  double grid_resolution_m = 0.01;
  SonarInverseModel sonar_model;
  double trajectory_period_s = 0.1;  // one trajectory row per period of simulated time
};

struct TrajectoryRow {
  double time_s = 0.0;
  Pose2 truth;
  Pose2 odometry;
  VelocityCommand command;
  std::uint32_t bumpers = 0;
};

struct ScenarioMetrics {
  double duration_s = 0.0;
  std::uint64_t steps = 0;
  double distance_travelled_m = 0.0;  // along the true path
  double rotation_travelled_rad = 0.0;
  Pose2 final_truth;
  Pose2 final_odometry;
  double odometry_position_error_m = 0.0;
  double odometry_heading_error_rad = 0.0;
  double explored_area_m2 = 0.0;
  std::uint64_t sonar_readings = 0;
  std::uint64_t sonar_echoes = 0;
  std::uint64_t bumper_events = 0;  // presses (rising edges)
};

struct ScenarioResult {
  OccupancyGrid grid;
  std::vector<TrajectoryRow> trajectory;
  ScenarioMetrics metrics;
};

ScenarioResult runScenario(const ScenarioSpec& spec);

}  // namespace irgs
