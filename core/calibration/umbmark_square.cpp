#include "core/calibration/umbmark_square.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/calibration/profile_calibration.hpp"
#include "core/sim/diff_drive.hpp"

namespace irgs {

namespace {

constexpr double kArrival_m = 5e-4;
constexpr double kMinSpeed_mps = 0.01;
constexpr double kApproachGain = 1.0;  // 1/s
constexpr double kBrake = 0.7;         // use 70 % of the profile's deceleration
constexpr double kHeadingTolerance_rad = 2e-4;
constexpr double kMinTurnRate_radps = 0.02;
constexpr double kSettle_s = 0.3;

bool finitePositive(double v) {
  return std::isfinite(v) && v > 0.0;
}

}  // namespace

void TickOdometry::reset(std::int64_t left_ticks, std::int64_t right_ticks) {
  pose_ = Pose2{};
  left_ = left_ticks;
  right_ = right_ticks;
}

void TickOdometry::update(std::int64_t left_ticks, std::int64_t right_ticks) {
  const double d_left =
      static_cast<double>(left_ticks - left_) * metres_per_tick_ * odometry_.left_wheel_scale;
  const double d_right =
      static_cast<double>(right_ticks - right_) * metres_per_tick_ * odometry_.right_wheel_scale;
  left_ = left_ticks;
  right_ = right_ticks;
  pose_ = integrateArc(pose_, 0.5 * (d_left + d_right), (d_right - d_left) / odometry_.wheelbase_m);
}

UmbmarkSquareDriver::UmbmarkSquareDriver(UmbmarkDirection direction, double side_m,
                                         double speed_mps, double turn_rate_radps,
                                         const MotionLimits& limits)
    : sign_(direction == UmbmarkDirection::kCounterClockwise ? 1.0 : -1.0),
      side_m_(side_m),
      speed_mps_(std::min(speed_mps, limits.max_speed_mps)),
      turn_rate_radps_(std::min(turn_rate_radps, limits.max_turn_rate_radps)),
      accel_mps2_(limits.max_accel_mps2),
      turn_accel_radps2_(limits.max_turn_accel_radps2) {
  startLeg();
}

VelocityCommand UmbmarkSquareDriver::command(const Pose2& pose, const VelocityCommand& measured,
                                             double dt_s) {
  phase_time_s_ += dt_s;
  switch (phase_) {
    case Phase::kDrive: {
      const Vec2 dir(std::cos(heading_), std::sin(heading_));
      const double along = (corner_ - pose.position()).dot(dir);
      if (along <= kArrival_m)
        return enter(Phase::kSettleAfterLeg);
      const double offset = cross(dir, pose.position() - leg_start_);  // left of the leg > 0
      const double wanted = heading_ + std::atan(-2.0 * offset);
      const double v = std::min({speed_mps_, std::sqrt(2.0 * kBrake * accel_mps2_ * along),
                                 kApproachGain * along + kMinSpeed_mps});
      const double w = std::clamp(2.0 * wrapAngle(wanted - pose.theta), -0.3, 0.3);
      return {v, w};
    }
    case Phase::kTurn: {
      const double e = wrapAngle(heading_ - pose.theta);
      if (std::abs(e) <= kHeadingTolerance_rad)
        return enter(Phase::kSettleAfterTurn);
      const double rate = std::max(
          std::min({turn_rate_radps_, std::sqrt(2.0 * kBrake * turn_accel_radps2_ * std::abs(e)),
                    3.0 * std::abs(e)}),
          kMinTurnRate_radps);
      return {0.0, std::copysign(rate, e)};
    }
    case Phase::kSettleAfterLeg:
    case Phase::kSettleAfterTurn:
      if (std::abs(measured.linear_mps) < 1e-6 && std::abs(measured.angular_radps) < 1e-6 &&
          phase_time_s_ >= kSettle_s) {
        if (phase_ == Phase::kSettleAfterTurn) {
          enter(Phase::kDrive);
        } else if (++leg_ >= 4) {
          enter(Phase::kDone);
        } else {
          startLeg();
        }
      }
      return {};
    case Phase::kDone:
      return {};
  }
  return {};
}

VelocityCommand UmbmarkSquareDriver::enter(Phase phase) {
  phase_ = phase;
  phase_time_s_ = 0.0;
  return {};
}

void UmbmarkSquareDriver::startLeg() {
  heading_ = wrapAngle(sign_ * 0.5 * kPi * leg_);
  leg_start_ = corner_;
  corner_ = leg_start_ + side_m_ * Vec2(std::cos(heading_), std::sin(heading_));
  // Snap the corners to the exact square (cos(pi/2) is not exactly 0).
  corner_ = corner_.unaryExpr([](double c) { return std::round(c * 1e9) / 1e9; });
  enter(leg_ == 0 ? Phase::kDrive : Phase::kTurn);
}

namespace {

OdometryCorrection believedOdometry(const RobotProfile& believed) {
  if (believed.drive.type != DriveType::kDifferential)
    throw std::invalid_argument("UmbmarkSquareBehaviour: UMBmark needs a differential drive");
  if (!finitePositive(believed.drive.metresPerTick()) ||
      !finitePositive(believed.drive.wheelbase_m))
    throw std::invalid_argument(
        "UmbmarkSquareBehaviour: the profile needs wheel conversion and wheelbase > 0");
  const ProfileOdometry odometry = profileOdometry(believed);
  if (!odometry.error.empty())
    throw std::invalid_argument("UmbmarkSquareBehaviour: " + odometry.error);
  return odometry.odometry;
}

}  // namespace

UmbmarkSquareBehaviour::UmbmarkSquareBehaviour(const RobotProfile& believed,
                                               const UmbmarkSquareConfig& config)
    : config_(config),
      limits_(believed.limits),
      odometry_(believed.drive.metresPerTick(), believedOdometry(believed)) {
  if (!finitePositive(config.side_m) || !finitePositive(config.speed_mps) ||
      !finitePositive(config.turn_rate_radps) || !finitePositive(config.max_run_s))
    throw std::invalid_argument("UmbmarkSquareBehaviour: side, speeds and time limit must be > 0");
  status_.phase = "waiting for the first sample";
}

VelocityCommand UmbmarkSquareBehaviour::onSample(const TelemetrySample& sample) {
  if (status_.finished)
    return {};
  if (!start_time_s_) {
    start_time_s_ = sample.time_s;
    last_time_s_ = sample.time_s;
    odometry_.reset(sample.left_ticks, sample.right_ticks);
    true_start_ = sample.true_pose;
    driver_.emplace(config_.direction, config_.side_m, config_.speed_mps, config_.turn_rate_radps,
                    limits_);
  } else {
    odometry_.update(sample.left_ticks, sample.right_ticks);
  }
  if (true_start_ && sample.true_pose) {
    // The truth in the start frame: where the robot stood, facing +x.
    const Vec2 p = true_start_->toBody(sample.true_pose->position());
    true_pose_ = Pose2{p.x(), p.y(), wrapAngle(sample.true_pose->theta - true_start_->theta)};
  }
  const double dt_s = std::max(0.0, sample.time_s - last_time_s_);
  last_time_s_ = sample.time_s;
  const VelocityCommand command =
      driver_->command(odometry_.pose(), sample.measured_velocity, dt_s);
  const int leg = std::min(driver_->leg(), 3);
  status_.progress = std::min(1.0, static_cast<double>(driver_->leg()) / 4.0);
  status_.phase =
      std::string(toString(config_.direction)) + " leg " + std::to_string(leg + 1) + " of 4";
  if (driver_->done()) {
    status_.finished = true;
    status_.progress = 1.0;
    status_.phase = "done";
    status_.message = std::string("UMBmark ") + toString(config_.direction) + " square done";
    return {};
  }
  if (sample.time_s - *start_time_s_ > config_.max_run_s) {
    status_.finished = true;
    status_.failed = true;
    status_.phase = "timed out";
    status_.message = "UMBmark square did not finish within " +
                      std::to_string(static_cast<int>(config_.max_run_s)) + " s";
    return {};
  }
  return command;
}

BehaviourStatus UmbmarkSquareBehaviour::status() const {
  return status_;
}

}  // namespace irgs
