#include "core/behaviour/wall_follower.hpp"

#include <cmath>
#include <stdexcept>

#include "core/motion/host_adapters.hpp"

namespace irgs {

std::optional<std::string> wallFollowConfigError(const WallFollowConfig& config) {
  if (const char* problem = motion::wallFollowConfigProblem(config))
    return std::string(problem);
  return std::nullopt;
}

std::string describe(motion::WallFollowEvent event, double turn_rad) {
  using motion::WallFollowEvent;
  switch (event) {
    case WallFollowEvent::kWallAhead:
      return "wall ahead: turn " +
             std::to_string(static_cast<int>(std::lround(radToDeg(turn_rad)))) +
             " deg (revision a)";
    case WallFollowEvent::kCornerClear:
      return "wall ended: clear the corner (revision b)";
    case WallFollowEvent::kRestoreParallel:
      return "restore parallel (revision c)";
    case WallFollowEvent::kLost:
      return "wall lost: seeking";
    case WallFollowEvent::kBumper:
      return "bumper: back up";
    case WallFollowEvent::kBlockedBackUp:
      return "blocked: back up";
    case WallFollowEvent::kBlockedTurnAway:
      return "blocked: turn away";
    case WallFollowEvent::kBlockedCreep:
      return "blocked: creep forward";
    case WallFollowEvent::kBlockedTurnToward:
      return "blocked: turn toward the wall side";
    case WallFollowEvent::kPoseNotFinite:
      return "odometry pose not finite: stopped";
    case WallFollowEvent::kNone:
    case WallFollowEvent::kCornerTurn:
      break;
  }
  return {};
}

WallFollower::WallFollower(const RobotProfile& profile, WallFollowConfig config)
    : geometry_(std::make_unique<motion::MotionGeometry>(motion::motionGeometryOf(profile))) {
  if (const auto err = wallFollowConfigError(config))
    throw std::invalid_argument("WallFollowConfig: " + *err);
  if (!motion::findSonarRoles(*geometry_).canFollow(config.wall_on_left))
    throw std::invalid_argument("robot profile '" + profile.name +
                                "' has no forward sonar and side sonar on the wall side");
  control_ = std::make_unique<motion::WallFollowControl>(*geometry_, config);
}

void WallFollower::setWallOnLeft(bool on_left) {
  if (!control_->setWallOnLeft(on_left))
    throw std::invalid_argument("robot profile has no side sonar on that side");
}

VelocityCommand WallFollower::onSample(const TelemetrySample& sample) {
  const VelocityCommand command = control_->step(motion::motionInputOf(sample));
  if (std::string text = describe(control_->event(), control_->eventTurn_rad()); !text.empty())
    message_ = std::move(text);
  return command;
}

BehaviourStatus WallFollower::status() const {
  BehaviourStatus s;
  s.phase = motion::toString(control_->mode());
  s.message = message_;
  return s;
}

}  // namespace irgs
