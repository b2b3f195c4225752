#pragma once
// Wall following with the side sonars, as the thesis robot does it on its own controller
// (003_…, section 4.1, digest 4.5-4.6 and 7.2): drive with the chosen side parallel to the wall
// at a set distance; at a wall ahead stop and turn by the front-sonar right-triangle angle in
// 15-degree quanta (revision (a)); when the wall ends (convex corner) drive on until the body
// clears it and turn toward it (revision (b)); restore parallel with an on-the-spot quantised
// turn when the two side sonars show 15 degrees or more (revision (c)); keep within the valid
// sonar distance, steering back when the wall drifts away (revision (d)). A bumper backs the
// robot off; a move blocked for blocked_s climbs the escape ladder.
//
// Firmware-grade: fixed-size state, no heap, no exceptions, no strings; one step per control
// period on the odometry pose and the sonar readings only. What happened in a step is an event
// (event()), which the host adapter (core/behaviour/wall_follower.hpp) words for people.

#include <cstdint>
#include <optional>

#include "core/motion/escape_ladder.hpp"
#include "core/motion/motion_geometry.hpp"
#include "core/motion/motion_input.hpp"
#include "core/motion/sonar_memory.hpp"
#include "core/motion/turn_control.hpp"

namespace irgs::motion {

struct WallFollowConfig {
  double distance_m = 0.3;  // body origin to wall, perpendicular
  bool wall_on_left = false;
  double speed_mps = 0.2;
  double turn_rate_radps = degToRad(60.0);         // on-the-spot turns
  double valid_distance_m = 1.0;                   // (d): readings beyond are not used
  double turn_quantum_rad = degToRad(15.0);        // all on-the-spot turns are multiples of this
  double parallel_threshold_rad = degToRad(15.0);  // (c): correct when off by this or more
  double front_margin_m = 0.12;  // a wall ahead closer than distance_m + this stops the robot
  double lost_margin_m = 0.3;    // a side wall farther than distance_m + this has ended
  double distance_gain_rad_per_m = 2.0;      // (d) approach angle per metre of distance error
  double max_approach_rad = degToRad(30.0);  // (d) steepest approach back to the set distance
  double heading_gain = 2.0;                 // omega = gain * heading error (1/s)
  double back_up_m = 0.08;                   // after a bumper hit
  // In contact this long while turning or backing up: the body is blocked (a corner on an
  // obstacle, the wheels stalled). The escape ladder (escape_ladder.hpp) picks the next move:
  // back up, turn away from the wall side, creep forward, turn toward it.
  double blocked_s = 1.0;
};

// What is wrong with the config (non-positive distances or speeds, valid distance not beyond
// the set distance, ...), or null.
const char* wallFollowConfigProblem(const WallFollowConfig& config);

enum class WallFollowMode {
  kSeek,
  kFollow,
  kTurn,
  kClear,
  kReacquire,
  kBackUp,
  kEscapeForward,
  kLost
};
const char* toString(WallFollowMode mode);

// What a step did that is worth telling (the last one when several happened in one step).
enum class WallFollowEvent : std::uint8_t {
  kNone,
  kWallAhead,        // revision (a): a turn of eventTurn_rad() started
  kCornerClear,      // revision (b): the wall ended, driving past the corner
  kCornerTurn,       // revision (b): the quarter turn round the corner started
  kRestoreParallel,  // revision (c): a turn of eventTurn_rad() started
  kLost,             // four reacquire turns found no wall: seeking again
  kBumper,           // contact: backing up
  kBlockedBackUp,    // escape ladder rungs
  kBlockedTurnAway,
  kBlockedCreep,
  kBlockedTurnToward,
  kPoseNotFinite,  // the odometry pose is not finite: stopped
};

class WallFollowControl {
 public:
  // True when the config is valid and the geometry has a forward sonar and a side sonar on the
  // wall side; the constructor's precondition.
  static bool usable(const MotionGeometry& geometry, const WallFollowConfig& config);

  // `geometry` must outlive the controller. Precondition: usable(geometry, config).
  WallFollowControl(const MotionGeometry& geometry, const WallFollowConfig& config);

  // One control step: the velocity to hold until the next.
  VelocityCommand step(const MotionInput& input);

  // Starts over in seek mode (drive straight until a wall), forgetting readings older than now.
  void restart();
  // Switches the followed side; false (nothing changed) when that side has no sonar.
  bool setWallOnLeft(bool on_left);

  WallFollowEvent event() const { return event_; }
  // The heading the last step's command steers toward (a turn's target, the held heading of a
  // straight move, the approach heading of (d) while following), or nothing when it backs up or
  // stops.
  std::optional<double> headingSetpoint() const { return heading_setpoint_; }
  double eventTurn_rad() const { return event_turn_rad_; }
  WallFollowMode mode() const { return mode_; }
  // True while the robot is following a wall it sees (not turning, seeking or reacquiring).
  bool following() const { return mode_ == WallFollowMode::kFollow; }
  const WallFollowConfig& config() const { return config_; }
  int turnCount() const { return turns_; }                  // on-the-spot turns started
  int parallelCorrections() const { return corrections_; }  // revision (c) turns
  int cornerTurns() const { return corner_turns_; }         // revisions (a) and (b)
  int bumps() const { return bumps_; }
  double distanceTravelled_m() const { return distance_m_; }
  // Wall angle relative to the heading (revision (c) right triangle) from the last step that
  // saw the wall with both side sonars, nullopt otherwise. CCW positive.
  std::optional<double> wallAngle() const { return wall_angle_; }
  const SonarMemory& sonar() const { return view_; }

 private:
  VelocityCommand startTurn(double turn_rad, WallFollowMode next, const Pose2& pose);
  VelocityCommand handleWallAhead(const Pose2& pose);
  bool passageAhead(const Pose2& pose) const;
  VelocityCommand follow(const Pose2& pose);
  VelocityCommand escapeBlocked(const Pose2& pose);
  VelocityCommand modeStep(const MotionInput& input, const Pose2& pose);
  void startStraight(WallFollowMode mode, const Pose2& pose);
  bool escaping() const;  // backing up, turning or creeping forward: contact is expected
  void note(WallFollowEvent event, double turn_rad = 0.0);
  std::optional<double> setpointFor(const VelocityCommand& command, const Pose2& pose) const;
  std::optional<double> sideWallDistance() const;  // front side sonar, within the present limit

  WallFollowConfig config_;
  SonarMemory view_;
  double side_sign_ = -1.0;  // +1 wall on the left
  WallFollowMode mode_ = WallFollowMode::kSeek;
  WallFollowMode next_mode_ = WallFollowMode::kFollow;
  double target_heading_ = 0.0;
  TurnProgress turn_progress_;  // of the turn to target_heading_
  double hold_heading_ = 0.0;
  Vec2 leg_start_ = Vec2::Zero();
  double leg_length_m_ = 0.0;
  double last_side_m_ = 0.0;
  int lost_count_ = 0;
  int skew_count_ = 0;
  int reacquire_turns_ = 0;
  int turns_ = 0;
  int corrections_ = 0;
  int corner_turns_ = 0;
  int bumps_ = 0;
  EscapeLadder escape_;
  double distance_m_ = 0.0;
  bool have_pose_ = false;
  Pose2 last_pose_;
  double now_s_ = 0.0;
  double measured_rate_radps_ = 0.0;  // the current step's, for the turns started in it
  WallFollowEvent event_ = WallFollowEvent::kNone;
  std::optional<double> heading_setpoint_;
  double follow_heading_ = 0.0;  // what (d) steers toward while following
  double event_turn_rad_ = 0.0;
  std::optional<double> wall_angle_;
  std::optional<double> contact_since_s_;  // in contact while turning or backing up, since
};

}  // namespace irgs::motion
