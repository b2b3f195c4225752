#include "core/mission/map_building_config.hpp"

#include <cmath>

namespace irgs {

std::optional<std::string> mapBuildingConfigError(const MapBuildingConfig& c) {
  if (const char* err = motion::wallFollowConfigProblem(c.follow))
    return std::string("follow: ") + err;
  const auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  if (!std::isfinite(c.turn_quantum_rad) || c.turn_quantum_rad < 0.0 ||
      c.turn_quantum_rad > degToRad(90.0))
    return "turn_quantum_rad must be in [0, 90 deg]";
  if (!positive(c.index_spacing_m) || !positive(c.closure_radius_m) ||
      !positive(c.min_loop_length_m))
    return "index spacing, closure radius and minimum loop length must be > 0";
  if (c.closure_radius_m >= c.min_loop_length_m)
    return "closure_radius_m must be smaller than min_loop_length_m";
  if (!positive(c.map_valid_distance_m) || !positive(c.grid_resolution_m) ||
      !positive(c.explore_cell_m) || c.explore_cell_m < c.grid_resolution_m)
    return "map_valid_distance_m, grid_resolution_m > 0 and explore_cell_m >= grid resolution";
  if (!std::isfinite(c.clearance_margin_m) || c.clearance_margin_m < 0.0)
    return "clearance_margin_m must be >= 0";
  if (!positive(c.travel_speed_mps) || !positive(c.max_time_s) || !positive(c.max_distance_m))
    return "travel speed and budgets must be > 0";
  if (!std::isfinite(c.heading_gate_base_rad) || c.heading_gate_base_rad < 0.0 ||
      !std::isfinite(c.heading_gate_per_m) || c.heading_gate_per_m < 0.0 ||
      !std::isfinite(c.heading_gate_per_turn) || c.heading_gate_per_turn < 0.0 ||
      !std::isfinite(c.heading_confirm_rad) || c.heading_confirm_rad < 0.0)
    return "heading gate and confirmation tolerances must be finite and >= 0";
  if (!std::isfinite(c.heading_walk_rad2_per_m) || c.heading_walk_rad2_per_m < 0.0 ||
      !std::isfinite(c.heading_walk_rad2_per_rad) || c.heading_walk_rad2_per_rad < 0.0 ||
      !positive(c.heading_fit_floor_rad) || !positive(c.obstacle_fit_floor_rad))
    return "heading random walk must be finite and >= 0, fit floors > 0";
  if (!positive(c.wall_ranging_gate_m) || !std::isfinite(c.wall_ranging_gain) ||
      c.wall_ranging_gain <= 0.0 || c.wall_ranging_gain > 1.0)
    return "wall_ranging_gate_m must be > 0 and wall_ranging_gain in (0, 1]";
  if (!positive(c.max_obstacle_loop_m) || c.max_obstacle_loop_m <= c.min_loop_length_m)
    return "max_obstacle_loop_m must be > min_loop_length_m";
  if (!std::isfinite(c.explore_range_m) || c.explore_range_m < 0.0)
    return "explore_range_m must be finite and >= 0";
  if (!positive(c.position_gate_m))
    return "position_gate_m must be > 0";
  if (const auto err = sonarInverseModelError(c.sonar_model))
    return "sonar_model: " + *err;
  return std::nullopt;
}

std::string_view toString(MapBuildingPhase phase) {
  switch (phase) {
    case MapBuildingPhase::kScan:
      return "scan";
    case MapBuildingPhase::kSeekWall:
      return "seek wall";
    case MapBuildingPhase::kFollowWall:
      return "follow wall";
    case MapBuildingPhase::kLoopClosed:
      return "loop closed";
    case MapBuildingPhase::kInterior:
      return "interior";
    case MapBuildingPhase::kObstacle:
      return "obstacle";
    case MapBuildingPhase::kDone:
      return "done";
    case MapBuildingPhase::kFailed:
      return "failed";
  }
  return "?";
}

}  // namespace irgs
