#pragma once
// Autonomous sonar map building as the thesis robot does it (003_…, Fig. 3.7; digest 4.5):
// scan, head for the nearest wall preferring the initial heading, follow walls with the wall on
// the LEFT (the room is traced clockwise, A003-6) dropping position indices at a fixed spacing,
// close the loop on returning to an earlier index, then explore the interior: plan on the grid
// built so far to unknown-but-reachable areas and to sonar evidence of unvisited obstacles, and
// circumnavigate every obstacle met counter-clockwise (obstacle on the left) until its own loop
// closes. A loop traced counter-clockwise is an obstacle: when the first "wall" was one (the
// third thesis map) the robot records it and goes on to the real wall. Finishes when the
// outline is closed and no reachable unknown area or unvisited obstacle remains inside it; a
// time or distance budget ends it as failed with the reason.
//
// Everything runs on the odometry pose and the sonar readings (host and robot split: docs/
// map-building.md). The grid is this behaviour's own, built from the samples it consumes.

#include <optional>
#include <string>
#include <vector>

#include "core/behaviour/behaviour.hpp"
#include "core/motion/escape_ladder.hpp"
#include "core/motion/turn_control.hpp"
#include "core/behaviour/sonar_view.hpp"
#include "core/behaviour/wall_follower.hpp"
#include "core/mapping/occupancy_grid.hpp"
#include "core/mapping/sonar_mapper.hpp"
#include "core/robot/robot_profile.hpp"

namespace irgs {

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

class MapBuildingBehaviour : public Behaviour {
 public:
  // Throws std::invalid_argument for a bad config or a profile the wall follower cannot use.
  MapBuildingBehaviour(const RobotProfile& profile, MapBuildingConfig config = {});

  VelocityCommand onSample(const TelemetrySample& sample) override;
  BehaviourStatus status() const override;
  std::string_view name() const override { return "map building"; }

  MapBuildingPhase phase() const { return phase_; }
  // Indices dropped so far in the current wall or obstacle loop.
  const std::vector<Vec2>& positionIndices() const { return indices_; }
  // Every index dropped in the run, in order (for drawing).
  const std::vector<Vec2>& allIndices() const { return all_indices_; }
  const std::optional<TracedLoop>& outline() const { return outline_; }
  const std::vector<TracedLoop>& obstacleLoops() const { return obstacle_loops_; }
  int obstacleCount() const { return static_cast<int>(obstacle_loops_.size()); }
  // True when the first surface followed turned out to be an obstacle (third thesis map).
  bool firstWallWasObstacle() const { return first_wall_was_obstacle_; }
  const OccupancyGrid& grid() const { return grid_; }
  const MapBuildingConfig& config() const { return config_; }
  double distanceTravelled_m() const { return distance_m_; }
  int interiorTargetsVisited() const { return targets_visited_; }
  // The pose the behaviour works in: odometry with the heading revisions applied.
  const Pose2& pose() const { return pose_; }
  double headingCorrection_rad() const { return heading_offset_; }
  int headingCorrections() const { return heading_corrections_; }
  int positionCorrections() const { return position_corrections_; }
  // Sonar readings that moved the pose across a room wall (ranging, after the outline closed).
  int rangeCorrections() const { return range_corrections_; }
  // Straight-wall fits whose correction disagreed with the drift expected since the last one.
  int headingRejections() const { return heading_rejections_; }
  // The learned odometry heading error: per metre driven and per radian turned.
  double learnedDrift_radpm() const { return drift_radpm_; }
  double learnedTurnScaleError() const { return turn_scale_error_; }

 private:
  // kCreep and kEscapeTurn are escape moves (escapeBlockedMove); after them the behaviour
  // re-plans from where the body got free.
  enum class Move {
    kNone,
    kTurn,
    kDrive,
    kFaceObstacle,
    kApproach,
    kBackUp,
    kCreep,
    kEscapeTurn,
    kPause
  };
  struct Target {
    Vec2 position = Vec2::Zero();
    bool obstacle = false;
    Vec2 obstacle_point = Vec2::Zero();
    std::vector<Vec2> path;
  };

  VelocityCommand fail(const std::string& why);
  VelocityCommand scan(const Pose2& pose);
  VelocityCommand followStep(const TelemetrySample& sample, const Pose2& pose);
  VelocityCommand onLoopClosed(const Pose2& pose, std::size_t from_index);
  VelocityCommand interior(const TelemetrySample& sample, const Pose2& pose);
  void escapeBlockedMove(const TelemetrySample& sample, const Pose2& pose);
  VelocityCommand startFollowing(const Pose2& pose, MapBuildingPhase phase);
  std::optional<Target> chooseTarget(const Pose2& pose);
  bool explained(const Vec2& p) const;
  void blacklist(const Vec2& p, double radius_m);

  MapBuildingConfig config_;
  RobotProfile profile_;
  SonarView view_;
  WallFollower follower_;
  SonarMapper mapper_;
  OccupancyGrid grid_;
  SonarMapper explore_mapper_;
  OccupancyGrid explore_grid_;  // long-range free-space knowledge (explore_range_m)
  MapBuildingPhase phase_ = MapBuildingPhase::kScan;
  MapBuildingPhase after_pause_ = MapBuildingPhase::kInterior;
  std::string message_;
  double body_radius_m_ = 0.0;

  // Odometry bookkeeping.
  bool started_ = false;
  double start_time_s_ = 0.0;
  double now_s_ = 0.0;
  Pose2 last_pose_;
  double distance_m_ = 0.0;

  // Heading revision.
  Pose2 pose_;
  Pose2 last_odometry_;
  double heading_offset_ = 0.0;
  double drift_radpm_ = 0.0;  // learned heading drift per metre driven
  double distance_at_correction_ = 0.0;
  int heading_corrections_ = 0;
  int heading_rejections_ = 0;
  double turned_since_correction_rad_ = 0.0;  // |angle| turned (odometry)
  double turn_scale_error_ = 0.0;             // learned heading error per radian turned
  double drift_normal_[3] = {0.0, 0.0, 0.0};  // least-squares sums d*d, d*t, t*t
  double drift_rhs_[2] = {0.0, 0.0};          // d*total, t*total
  double cumulative_distance_m_ = 0.0;        // odometry distance since the start
  double cumulative_turn_rad_ = 0.0;          // signed odometry turn since the start
  double cumulative_correction_rad_ = 0.0;    // revised minus raw odometry heading
  double heading_variance_ = 0.0;             // of the revised heading, rad^2
  std::optional<double> pending_error_;       // a large correction waiting for confirmation
  std::vector<Vec2> wall_points_;
  void fitWallHeading(const TelemetrySample& sample);
  struct WallLandmark {
    double direction = 0.0;  // [0, pi), on the lattice
    double offset = 0.0;     // along the normal (-sin, cos) of the direction, m
    double along_min = 0.0;  // extent along the direction, m
    double along_max = 0.0;
    bool forward = true;      // seen while driving along +direction (the wall's side)
    int epoch = 0;            // follow_epoch_ when seen
    double distance_m = 0.0;  // distance travelled when seen
    bool room = false;        // traced on the first loop round the room
  };
  std::vector<WallLandmark> landmarks_;
  int follow_epoch_ = 0;  // counts wall/obstacle follows and loop closures
  int range_corrections_ = 0;
  void rangeToRoomWalls(const TelemetrySample& sample);
  int position_corrections_ = 0;
  void reviseAcrossWall(double direction, const Vec2& mean, double along_min, double along_max);

  // Scan.
  double scan_start_heading_ = 0.0;
  double scan_turned_rad_ = 0.0;
  double scan_best_range_ = 0.0;
  double scan_best_heading_ = 0.0;
  double scan_initial_range_ = -1.0;

  // Loops.
  std::vector<Vec2> indices_;
  std::vector<double> index_distance_;  // loop path length at each index
  std::vector<double> index_heading_;
  std::vector<Vec2> all_indices_;
  double loop_distance_m_ = 0.0;
  double loop_interior_m_ = 0.0;  // of an obstacle loop, away from the room's outline
  double next_index_at_m_ = 0.0;
  std::optional<TracedLoop> outline_;
  std::vector<TracedLoop> obstacle_loops_;
  std::vector<TracedLoop> pocket_loops_;  // clockwise loops inside the room (obstacle pockets)
  std::optional<Vec2> obstacle_anchor_;   // the surface point the current obstacle loop began at
  std::vector<Vec2> obstacle_anchors_;    // where every obstacle loop so far began
  bool visitedOften(const Vec2& p) const;
  bool first_wall_was_obstacle_ = false;

  // Interior moves.
  Move move_ = Move::kNone;
  TurnProgress turn_progress_;  // of the kTurn / kFaceObstacle move
  EscapeLadder escape_;
  std::optional<double> contact_since_s_;  // in contact during a turn or back-up, since
  double move_heading_ = 0.0;
  Vec2 move_start_ = Vec2::Zero();
  double move_length_m_ = 0.0;
  double pause_until_s_ = 0.0;
  std::optional<Target> target_;
  std::size_t waypoint_ = 0;
  std::vector<Vec2> blacklist_;
  std::vector<double> blacklist_radius_;
  int targets_visited_ = 0;
  int failed_plans_ = 0;
};

}  // namespace irgs
