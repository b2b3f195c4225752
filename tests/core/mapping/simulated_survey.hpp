#pragma once
// Test support: builds an occupancy grid the way the robot would, by running the simulator.
// The robot stands on a lattice of poses over the free space reachable from the map's start
// (body clear of walls), turns through twelve headings at each, and every sonar reading of
// every step is integrated with the SonarMapper on the odometry pose. With idealSimConfig the
// readings are exact (no odometry error, no range noise, no dropouts).

#include <stdexcept>
#include <string>
#include <vector>

#include "core/mapping/occupancy_grid.hpp"
#include "core/mapping/sonar_mapper.hpp"
#include "core/planning/planning_grid.hpp"
#include "core/robot/robot_profile_file.hpp"
#include "core/sim/sim_presets.hpp"
#include "core/sim/simulator.hpp"
#include "core/world/map_file.hpp"

namespace irgs::test {

inline WorldMap loadBundledMap(const std::string& name) {
  const MapLoadResult loaded =
      loadMapFile(std::string(IRGS_SOURCE_DIR) + "/resources/maps/" + name + ".json");
  if (!loaded.map)
    throw std::runtime_error("bundled map " + name + " does not load");
  return *loaded.map;
}

inline RobotProfile thesisRobot() {
  const RobotProfileResult loaded =
      loadRobotProfileFile(std::string(IRGS_SOURCE_DIR) + "/resources/robots/thesis_robot.json");
  if (!loaded.profile)
    throw std::runtime_error("bundled thesis_robot.json does not load");
  return *loaded.profile;
}

struct SurveyOptions {
  double spacing_m = 0.3;     // lattice spacing
  double clearance_m = 0.25;  // robot centre to the nearest wall or obstacle
  double valid_distance_m = 3.0;
  int headings = 12;
};

// The lattice poses (heading 0) reachable from map.start without crossing geometry.
inline std::vector<Vec2> surveyPositions(const WorldMap& map, const SurveyOptions& options) {
  PlanningGridOptions grid_options;
  grid_options.robot_radius_m = options.clearance_m;
  const PlanningGrid grid = planningGridFromWorld(map, 0.05, grid_options, 0.1);
  const auto start = grid.worldToCell(map.start.position());
  if (!start || !grid.isFree(*start))
    throw std::runtime_error("survey: the map's start is not clear");
  std::vector<std::uint8_t> reached(grid.cellCount(), 0);
  std::vector<Cell> stack{*start};
  reached[grid.index(*start)] = 1;
  while (!stack.empty()) {
    const Cell c = stack.back();
    stack.pop_back();
    for (const Cell n : {Cell{c.col + 1, c.row}, Cell{c.col - 1, c.row}, Cell{c.col, c.row + 1},
                         Cell{c.col, c.row - 1}})
      if (grid.isFree(n) && reached[grid.index(n)] == 0) {
        reached[grid.index(n)] = 1;
        stack.push_back(n);
      }
  }
  std::vector<Vec2> out;
  const Box2 b = map.bounds();
  for (double y = b.min.y() + 0.5 * options.spacing_m; y < b.max.y(); y += options.spacing_m)
    for (double x = b.min.x() + 0.5 * options.spacing_m; x < b.max.x(); x += options.spacing_m) {
      const auto cell = grid.worldToCell({x, y});
      if (cell && reached[grid.index(*cell)] != 0)
        out.emplace_back(x, y);
    }
  return out;
}

inline OccupancyGrid surveyGrid(const WorldMap& map, const SurveyOptions& options = {},
                                SimConfig config = idealSimConfig()) {
  const RobotProfile robot = thesisRobot();
  Simulator sim(map, robot, config);
  const SonarMapper mapper(robot, {}, options.valid_distance_m);
  OccupancyGrid grid(0.01);
  // Enough steps for every sonar to fire once at each heading.
  double slowest_hz = 1e9;
  for (const SonarSpec& s : robot.sonars)
    slowest_hz = std::min(slowest_hz, s.rate_hz);
  const int steps = static_cast<int>(std::ceil(1.0 / (slowest_hz * config.dt_s)));
  TelemetrySample sample;
  for (const Vec2& p : surveyPositions(map, options))
    for (int h = 0; h < options.headings; ++h) {
      sim.resetPose({p.x(), p.y(), wrapAngle(2.0 * kPi * h / options.headings)});
      for (int s = 0; s < steps; ++s) {
        sim.step(sample);
        mapper.integrate(sample, grid);
      }
    }
  return grid;
}

}  // namespace irgs::test
