#pragma once
// Wall following as a host Behaviour: the robot-side controller (core/motion/wall_follow.hpp,
// thesis revisions (a)-(d)) fed one telemetry sample per step, with its events worded for the
// console. In-process tools and the host map-building behaviour use it; a robot runs the same
// controller itself as the FOLLOW_WALL primitive.

#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "core/behaviour/behaviour.hpp"
#include "core/motion/motion_geometry.hpp"
#include "core/motion/wall_follow.hpp"
#include "core/robot/robot_profile.hpp"

namespace irgs {

using WallFollowConfig = motion::WallFollowConfig;
using WallFollowMode = motion::WallFollowMode;

// What is wrong with the config (non-positive distances or speeds, valid distance not beyond
// the set distance, ...), or nothing.
std::optional<std::string> wallFollowConfigError(const WallFollowConfig& config);

class WallFollower : public Behaviour {
 public:
  // Throws std::invalid_argument for a bad config or a profile without a forward sonar and a
  // side sonar on the wall side.
  WallFollower(const RobotProfile& profile, WallFollowConfig config = {});

  VelocityCommand onSample(const TelemetrySample& sample) override;
  BehaviourStatus status() const override;
  std::string_view name() const override { return "wall follow"; }

  // Starts over in seek mode (drive straight until a wall), forgetting readings older than now.
  void restart() { control_->restart(); }
  // Switches the followed side (used by map building: walls and obstacles on the left). Throws
  // std::invalid_argument when that side has no sonar.
  void setWallOnLeft(bool on_left);

  WallFollowMode mode() const { return control_->mode(); }
  // True while the robot is following a wall it sees (not turning, seeking or reacquiring).
  bool following() const { return control_->following(); }
  const WallFollowConfig& config() const { return control_->config(); }
  int turnCount() const { return control_->turnCount(); }
  int parallelCorrections() const { return control_->parallelCorrections(); }
  int cornerTurns() const { return control_->cornerTurns(); }
  int bumps() const { return control_->bumps(); }
  double distanceTravelled_m() const { return control_->distanceTravelled_m(); }
  std::optional<double> wallAngle() const { return control_->wallAngle(); }

 private:
  // The geometry lives on the heap so the controller's reference to it survives a move.
  std::unique_ptr<motion::MotionGeometry> geometry_;
  std::unique_ptr<motion::WallFollowControl> control_;
  std::string message_;
};

// The console wording of a wall-follow event (empty for events that are not worded).
std::string describe(motion::WallFollowEvent event, double turn_rad);

}  // namespace irgs
