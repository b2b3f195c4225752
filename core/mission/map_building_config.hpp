#pragma once
// Configuration and vocabulary of autonomous sonar map building (003_…, Fig. 3.7; digest 4.5):
// the host mission (map_building_mission.hpp) and its pieces share them.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/mapping/sonar_mapper.hpp"
#include "core/motion/wall_follow.hpp"

namespace irgs {

using WallFollowConfig = motion::WallFollowConfig;

struct MapBuildingConfig {
  WallFollowConfig follow;                   // wall_on_left is forced true (A003-6)
  double turn_quantum_rad = degToRad(15.0);  // also applied to follow.turn_quantum_rad
  double index_spacing_m = 0.5;              // position indices along the followed wall
  double closure_radius_m = 0.35;            // back at an index when this close
  double min_loop_length_m = 1.5;            // path length before a loop may close
  // An obstacle loop that runs longer than this away from the room's walls is given up (several
  // obstacles packed closer than the follower's reach merge into one long loop); what it passed
  // counts as explained. (Along the outline it may run on: an obstacle near a wall can lead the
  // follower round the room, which closes clockwise and is tried again.)
  double max_obstacle_loop_m = 20.0;
  double map_valid_distance_m = 1.0;  // sonar readings mapped up to this range
  double grid_resolution_m = 0.01;
  double explore_cell_m = 0.1;  // coarse cell for interior targets and planning
  // Free space seen by sonar up to this range (beyond the mapping range) counts as explored for
  // the interior targets (a separate coarse knowledge grid; the built map is unchanged). 0: off.
  double explore_range_m = 3.0;
  double clearance_margin_m = 0.06;  // added to the body radius when planning
  double travel_speed_mps = 0.3;     // interior legs (known free space)
  // Frontiers (reachable free cells next to unknown space) anywhere, not only inside the first
  // closed outline: multi-room maps whose first loop did not enclose every room.
  bool explore_beyond_outline = true;
  // Position revision across walls: straight-wall fits on the first loop round the room are
  // kept as reference lines; a later fit on the same line (same lattice direction, overlapping,
  // offset within position_gate_m, no other parallel reference near) moves the pose across
  // the wall by the offset. Needs heading_lattice_rad > 0.
  bool position_revision = true;
  double position_gate_m = 0.3;
  // Ranging to room walls: once the outline is closed, a sonar whose cone holds the normal of a
  // room wall traced on the first loop, with nothing mapped in between, measures the distance
  // across it; within wall_ranging_gate_m of the predicted distance the pose moves along the
  // normal by wall_ranging_gain times the difference (per reading).
  bool wall_ranging = true;
  double wall_ranging_gate_m = 0.3;
  double wall_ranging_gain = 0.1;
  double max_time_s = 3600.0;      // budget (time since the first sample)
  double max_distance_m = 1500.0;  // budget (odometry path length)
  SonarInverseModel sonar_model;
  // Heading revision from walls (revision (c) carried into the map): walls are assumed to lie
  // on this lattice of directions in the start frame (the thesis rooms have 90- and 45-degree
  // walls). When the echo points of the left side sonars along heading_fit_length_m of wall
  // fit one straight line (total least squares, spread < 1.5 cm), its direction is snapped to the
  // nearest lattice direction when it is within heading_capture_rad, and the pose used for the map
  // is corrected by the difference. 0 switches it off (rooms with arbitrary wall directions).
  double heading_lattice_rad = degToRad(15.0);
  double heading_capture_rad = degToRad(7.0);
  double obstacle_heading_capture_rad = degToRad(1.5);  // faces of obstacles met inside
  double heading_fit_length_m = 0.8;
  // A single wrong line (an obstacle face off the lattice, a loop slipping onto a nearby wall)
  // must not rotate the map. With the learned drift removed, the heading error left since the
  // last revision is small and grows with distance and turning (wheel radii, wheelbase), so a
  // correction is accepted at once only within
  //   heading_gate_base_rad + heading_gate_per_m * distance + heading_gate_per_turn * |turned|
  // since the last accepted one. A larger one (still within the capture) on the outline is
  // accepted only when the next straight-wall fit asks for the same correction (within
  // heading_confirm_rad); on obstacle faces it is rejected.
  double heading_gate_base_rad = degToRad(1.0);
  double heading_gate_per_m = degToRad(0.3);
  double heading_gate_per_turn = 0.006;  // rad per rad turned (wheelbase error ~0.5 %)
  double heading_confirm_rad = degToRad(1.0);
  // An accepted correction is weighed against the heading's own uncertainty (scalar Kalman
  // update): the heading variance grows by these per metre driven and per radian turned (the
  // odometry error left after the learned model), a fitted line's variance is its fit variance
  // plus the square of a floor (walls not exactly on the lattice; obstacle faces more so).
  double heading_walk_rad2_per_m = degToRad(0.15) * degToRad(0.15);
  double heading_walk_rad2_per_rad = degToRad(0.5) * degToRad(0.5);
  double heading_fit_floor_rad = degToRad(0.1);
  double obstacle_fit_floor_rad = degToRad(0.3);
};

// What is wrong with the config, or nothing.
std::optional<std::string> mapBuildingConfigError(const MapBuildingConfig& config);

enum class MapBuildingPhase {
  kScan,
  kSeekWall,
  kFollowWall,
  kLoopClosed,
  kInterior,
  kObstacle,
  kDone,
  kFailed
};
std::string_view toString(MapBuildingPhase phase);

// A closed loop of position indices (odometry frame).
struct TracedLoop {
  std::vector<Vec2> indices;
  double signed_area_m2 = 0.0;  // > 0: counter-clockwise, an obstacle kept on the left
  bool obstacle = false;
};

}  // namespace irgs
