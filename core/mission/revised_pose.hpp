#pragma once
// The pose map building works in (host side, map frame): the robot's odometry with heading and
// position revisions applied — revision (c) carried into the map (straight-wall fits snapped to
// the heading lattice, weighed against the heading's own uncertainty), the odometry error model
// those revisions teach (drift per metre, scale error per radian turned), position revision
// across walls seen again (wall landmarks), and ranging to the room's walls once the outline is
// closed. docs/map-building.md, "Heading revision from walls", has the reasoning and figures.
//
// The robot's primitives run on its raw odometry; odometryOf() maps a map-frame pose back into
// the robot's odometry frame with the correction in force now.

#include <optional>
#include <vector>

#include "core/mapping/occupancy_grid.hpp"
#include "core/mission/map_building_config.hpp"
#include "core/motion/motion_geometry.hpp"
#include "core/robot/robot_profile.hpp"
#include "core/robot/telemetry.hpp"

namespace irgs {

class RevisedPose {
 public:
  RevisedPose(const RobotProfile& profile, const MapBuildingConfig& config);

  // Carries the odometry step since the previous call onto the revised pose, with the learned
  // error model removed. The first call starts the revised pose at the odometry pose.
  void onOdometry(const Pose2& odometry);

  // Where the robot is in its run when the echoes of a sample are fitted.
  struct WallContext {
    bool following = false;        // beside a wall it sees, wall on the left
    bool obstacle = false;         // the surface is an obstacle met inside (tighter capture)
    bool room_first_loop = false;  // tracing the room's outline for the first time
    int epoch = 0;                 // counts surfaces followed and loops closed
    double distance_m = 0.0;       // path driven since the start (map frame)
  };
  // Heading revision from a straight-wall fit of the left side sonars' echoes, and the position
  // revision across a wall seen before.
  void fitWall(const TelemetrySample& sample, const WallContext& context);
  // Moves the pose across room walls (first-loop landmarks) a sonar faces, when `grid` (the
  // built map) is clear up to them.
  void rangeToRoomWalls(const TelemetrySample& sample, const OccupancyGrid& grid);

  bool started() const { return started_; }
  const Pose2& pose() const { return pose_; }
  // The robot's odometry pose that corresponds to `map_pose` now.
  Pose2 odometryOf(const Pose2& map_pose) const;
  double headingCorrection_rad() const { return heading_offset_; }
  int headingCorrections() const { return heading_corrections_; }
  int headingRejections() const { return heading_rejections_; }
  int positionCorrections() const { return position_corrections_; }
  int rangeCorrections() const { return range_corrections_; }
  double learnedDrift_radpm() const { return drift_radpm_; }
  double learnedTurnScaleError() const { return turn_scale_error_; }

 private:
  void reviseAcrossWall(double direction, const Vec2& mean, double along_min, double along_max,
                        const WallContext& context);

  MapBuildingConfig config_;
  RobotProfile profile_;
  motion::SonarRoles roles_;
  bool started_ = false;
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
  struct WallLandmark {
    double direction = 0.0;  // [0, pi), on the lattice
    double offset = 0.0;     // along the normal (-sin, cos) of the direction, m
    double along_min = 0.0;  // extent along the direction, m
    double along_max = 0.0;
    bool forward = true;      // seen while driving along +direction (the wall's side)
    int epoch = 0;            // the follow epoch when seen
    double distance_m = 0.0;  // distance travelled when seen
    bool room = false;        // traced on the first loop round the room
  };
  std::vector<WallLandmark> landmarks_;
  int range_corrections_ = 0;
  int position_corrections_ = 0;
};

}  // namespace irgs
