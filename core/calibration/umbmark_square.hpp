#pragma once
// The UMBmark square as a robot drives it on its own odometry (Borenstein & Feng 1996): four legs
// of side L with on-the-spot turns in between, clockwise or counter-clockwise, ending where the
// odometry started. Used by the simulated procedure (umbmark_run.hpp) and, as a Behaviour, on
// any robot behind the Robot interface (a linked robot: the calibration wizard).
//
// The odometry is integrated from the encoder ticks with the *believed* parameters (the profile's
// wheel conversion, wheelbase and per-wheel calibration scales), never with the robot's own pose:
// that is the odometry being calibrated.

#include <cstdint>
#include <optional>
#include <string_view>

#include "core/behaviour/behaviour.hpp"
#include "core/calibration/umbmark.hpp"
#include "core/robot/robot_profile.hpp"

namespace irgs {

// Dead reckoning from cumulative encoder ticks with per-wheel scales and a wheelbase.
class TickOdometry {
 public:
  TickOdometry(double metres_per_tick, const OdometryCorrection& odometry)
      : metres_per_tick_(metres_per_tick), odometry_(odometry) {}

  // The pose becomes the origin; the ticks are the reference the next update counts from.
  void reset(std::int64_t left_ticks, std::int64_t right_ticks);
  void update(std::int64_t left_ticks, std::int64_t right_ticks);
  const Pose2& pose() const { return pose_; }

 private:
  double metres_per_tick_;
  OdometryCorrection odometry_;
  Pose2 pose_;
  std::int64_t left_ = 0;
  std::int64_t right_ = 0;
};

// Drives the square on the believed pose: leg, stop, on-the-spot turn, stop, ... four legs,
// ending where the odometry started. Speeds brake in time for the profile's accelerations so
// the robot neither overshoots a corner nor a heading.
class UmbmarkSquareDriver {
 public:
  UmbmarkSquareDriver(UmbmarkDirection direction, double side_m, double speed_mps,
                      double turn_rate_radps, const MotionLimits& limits);

  bool done() const { return phase_ == Phase::kDone; }
  int leg() const { return leg_; }  // 0..3 while driving, 4 when done
  // The command for the next `dt_s`, given the believed pose and the measured velocity (the
  // driver waits for the robot to stand still after each leg and turn).
  VelocityCommand command(const Pose2& pose, const VelocityCommand& measured, double dt_s);

 private:
  enum class Phase { kDrive, kSettleAfterLeg, kTurn, kSettleAfterTurn, kDone };
  VelocityCommand enter(Phase phase);
  void startLeg();

  double sign_;
  double side_m_;
  double speed_mps_;
  double turn_rate_radps_;
  double accel_mps2_;
  double turn_accel_radps2_;
  Phase phase_ = Phase::kDrive;
  double phase_time_s_ = 0.0;
  int leg_ = 0;
  double heading_ = 0.0;
  Vec2 leg_start_ = Vec2::Zero();
  Vec2 corner_ = Vec2::Zero();
};

struct UmbmarkSquareConfig {
  UmbmarkDirection direction = UmbmarkDirection::kClockwise;
  double side_m = 4.0;
  double speed_mps = 0.2;
  double turn_rate_radps = 0.5;
  double max_run_s = 900.0;  // the behaviour fails after this long (session time)
};

// One square on a robot behind the Robot interface, as a Behaviour: the first sample sets the
// odometry origin (start frame = where the robot stands, facing +x), each later one advances the
// tick odometry and the driver. Finished when the robot stands still at its believed start.
// Throws std::invalid_argument for a non-differential profile, a believed profile without wheel
// conversion or wheelbase, a malformed calibration object, or a non-positive side or speed.
class UmbmarkSquareBehaviour : public Behaviour {
 public:
  UmbmarkSquareBehaviour(const RobotProfile& believed, const UmbmarkSquareConfig& config);

  VelocityCommand onSample(const TelemetrySample& sample) override;
  BehaviourStatus status() const override;
  std::string_view name() const override { return "UMBmark square"; }

  // The believed final position in the start frame (valid once finished).
  const Pose2& odometryPose() const { return odometry_.pose(); }
  // The true pose in the start frame when the robot reports truth (the simulator), else nothing.
  const std::optional<Pose2>& truePose() const { return true_pose_; }

 private:
  UmbmarkSquareConfig config_;
  MotionLimits limits_;
  TickOdometry odometry_;
  std::optional<UmbmarkSquareDriver> driver_;
  std::optional<double> start_time_s_;
  double last_time_s_ = 0.0;
  std::optional<Pose2> true_start_;
  std::optional<Pose2> true_pose_;
  BehaviourStatus status_;
};

}  // namespace irgs
