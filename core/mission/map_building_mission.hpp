#pragma once
// Autonomous sonar map building as the thesis splits it between robot and host (003_…, section
// 4.1 and Fig. 3.7; digest 4.5 and 7.2). The robot runs the motion primitives — the scan turn,
// turns, wall following with the four revisions, the traveling segments, the approach to an
// obstacle — on its own odometry; this host mission keeps the map, the position indices and the
// closed-loop check, the pose revisions, the interior target search and the decision that the
// map is complete, and reacts to the robot's reports and telemetry (which over a real link come
// late, sparse, or not at all for a while).
//
// The procedure: scan; head for the nearest wall preferring the initial heading; follow walls
// with the wall on the LEFT (the room is traced clockwise, A003-6) dropping indices; close the
// loop on returning to an earlier index; then explore the interior (frontiers and unvisited
// obstacles, interior_targets.hpp) and circumnavigate every obstacle met counter-clockwise
// until its own loop closes. A counter-clockwise loop is an obstacle: when the first "wall" was
// one (the third thesis map) the robot records it and goes on to the real wall. Finishes when
// no target remains; a time or distance budget ends it as failed with the reason.
//
// Pieces, each tested on its own: RevisedPose (the map frame), LoopTracker (indices and
// closure), ExploredRecord (what is explained), chooseInteriorTarget (where next).

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/mapping/occupancy_grid.hpp"
#include "core/mapping/sonar_mapper.hpp"
#include "core/mission/explored_record.hpp"
#include "core/mission/interior_targets.hpp"
#include "core/mission/loop_tracker.hpp"
#include "core/mission/map_building_config.hpp"
#include "core/mission/mission.hpp"
#include "core/mission/revised_pose.hpp"
#include "core/motion/escape_ladder.hpp"
#include "core/motion/sonar_memory.hpp"
#include "core/robot/robot_profile.hpp"

namespace irgs {

class MapBuildingMission final : public Mission {
 public:
  // Throws std::invalid_argument for a bad config or a profile without the sonars to follow a
  // wall on the left.
  MapBuildingMission(const RobotProfile& profile, MapBuildingConfig config = {});

  void onSample(const TelemetrySample& sample) override;
  void onReport(const motion::MotionReport& report) override;
  std::optional<MissionRequest> takeRequest() override;
  BehaviourStatus status() const override;
  std::string_view name() const override { return "map building"; }

  MapBuildingPhase phase() const { return phase_; }
  // Indices dropped so far in the current wall or obstacle loop (map frame).
  const std::vector<Vec2>& positionIndices() const { return loops_.indices(); }
  // Every index dropped in the run, in order (for drawing).
  const std::vector<Vec2>& allIndices() const { return loops_.allIndices(); }
  const std::optional<TracedLoop>& outline() const { return record_.outline(); }
  const std::vector<TracedLoop>& obstacleLoops() const { return record_.obstacles(); }
  int obstacleCount() const { return static_cast<int>(record_.obstacles().size()); }
  // True when the first surface followed turned out to be an obstacle (third thesis map).
  bool firstWallWasObstacle() const { return first_wall_was_obstacle_; }
  const OccupancyGrid& grid() const { return grid_; }
  const MapBuildingConfig& config() const { return config_; }
  double distanceTravelled_m() const { return distance_m_; }
  int interiorTargetsVisited() const { return targets_visited_; }
  // The pose the mission works in: odometry with the revisions applied.
  const Pose2& pose() const { return revised_.pose(); }
  const RevisedPose& revisedPose() const { return revised_; }
  int primitivesStarted() const { return next_id_ - 1; }

 private:
  // What the running primitive is for.
  enum class Move {
    kNone,
    kScan,          // the full turn of the scan
    kSeekTurn,      // toward the chosen wall, then follow
    kFollow,        // a surface (wall or obstacle), loops tracked here
    kTravel,        // segments to an interior target
    kFaceObstacle,  // turn toward an obstacle target
    kApproach,      // drive toward it until a wall is ahead
    kBackUp,        // escape moves
    kCreep,
    kEscapeTurn,
    kPause,  // no primitive: a second's rest after a loop closed
  };

  void send(const motion::PrimitiveSpec& spec, Move move);
  void cancelPrimitive();
  void fail(const std::string& why);
  void startFollowing(MapBuildingPhase phase);
  void turnTo(double map_heading_rad, Move move);
  void onLoopClosed(std::size_t from_index);
  void giveUpObstacleLoop();
  void trackFollow(const TelemetrySample& sample);
  void scanSample();
  void afterScan();
  void afterPause();
  void nextInteriorTarget();
  void arrived();
  void frontWall();
  void escape(bool blocked_move_was_turn);
  void resume();
  void onFinal(const motion::MotionReport& report);
  bool following() const;
  Vec2 toOdometry(const Vec2& map_point) const;

  MapBuildingConfig config_;
  RobotProfile profile_;
  motion::MotionGeometry geometry_;
  motion::SonarMemory sonar_;  // what the host sees ahead (scan, walls met), map-frame samples
  RevisedPose revised_;
  SonarMapper mapper_;
  OccupancyGrid grid_;
  SonarMapper explore_mapper_;
  OccupancyGrid explore_grid_;  // long-range free-space knowledge (explore_range_m)
  ExploredRecord record_;
  LoopTracker loops_;
  MapBuildingPhase phase_ = MapBuildingPhase::kScan;
  MapBuildingPhase after_pause_ = MapBuildingPhase::kInterior;
  std::string message_;
  double body_radius_m_ = 0.0;

  // Requests and the primitive in flight.
  std::optional<MissionRequest> request_;
  std::uint16_t next_id_ = 1;
  std::uint16_t active_id_ = 0;  // 0: none
  Move move_ = Move::kNone;
  motion::PrimitiveSpec last_spec_;
  int safety_retries_ = 0;
  int follower_mode_ = 0;  // motion::WallFollowMode of the robot's follower, from kMode reports

  // Bookkeeping on the map-frame pose.
  bool started_ = false;
  double start_time_s_ = 0.0;
  double now_s_ = 0.0;
  Pose2 last_pose_;
  double distance_m_ = 0.0;
  int follow_epoch_ = 0;  // counts surfaces followed and loops closed
  double loop_interior_m_ = 0.0;
  std::optional<Vec2> obstacle_anchor_;
  bool first_wall_was_obstacle_ = false;

  // Scan.
  double scan_start_heading_ = 0.0;
  double scan_turned_rad_ = 0.0;
  double scan_best_range_ = 0.0;
  double scan_best_heading_ = 0.0;
  double scan_initial_range_ = -1.0;

  // Interior.
  double pause_until_s_ = 0.0;
  std::optional<InteriorTarget> target_;
  EscapeLadder escape_;
  int targets_visited_ = 0;
};

}  // namespace irgs
