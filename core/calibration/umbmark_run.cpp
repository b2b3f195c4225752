#include "core/calibration/umbmark_run.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/calibration/profile_calibration.hpp"
#include "core/sim/diff_drive.hpp"
#include "core/sim/simulator.hpp"
#include "core/world/world_map.hpp"

namespace irgs {

namespace {

void require(bool condition, const std::string& what) {
  if (!condition)
    throw std::invalid_argument("runUmbmarkInSimulator: " + what);
}

bool finitePositive(double v) {
  return std::isfinite(v) && v > 0.0;
}

// Odometry from encoder ticks with the believed parameters (per-wheel scales, wheelbase).
class TickOdometry {
 public:
  TickOdometry(const RobotProfile& believed, const OdometryCorrection& odometry)
      : metres_per_tick_(believed.drive.metresPerTick()), odometry_(odometry) {}

  void reset(std::int64_t left_ticks, std::int64_t right_ticks) {
    pose_ = Pose2{};
    left_ = left_ticks;
    right_ = right_ticks;
  }
  void update(std::int64_t left_ticks, std::int64_t right_ticks) {
    const double d_left =
        static_cast<double>(left_ticks - left_) * metres_per_tick_ * odometry_.left_wheel_scale;
    const double d_right =
        static_cast<double>(right_ticks - right_) * metres_per_tick_ * odometry_.right_wheel_scale;
    left_ = left_ticks;
    right_ = right_ticks;
    pose_ =
        integrateArc(pose_, 0.5 * (d_left + d_right), (d_right - d_left) / odometry_.wheelbase_m);
  }
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
class SquareDriver {
 public:
  SquareDriver(UmbmarkDirection direction, double side_m, double speed_mps, double turn_rate_radps,
               const MotionLimits& limits)
      : sign_(direction == UmbmarkDirection::kCounterClockwise ? 1.0 : -1.0),
        side_m_(side_m),
        speed_mps_(std::min(speed_mps, limits.max_speed_mps)),
        turn_rate_radps_(std::min(turn_rate_radps, limits.max_turn_rate_radps)),
        accel_mps2_(limits.max_accel_mps2),
        turn_accel_radps2_(limits.max_turn_accel_radps2) {
    startLeg();
  }

  bool done() const { return phase_ == Phase::kDone; }

  VelocityCommand command(const Pose2& pose, const VelocityCommand& measured, double dt_s) {
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

 private:
  enum class Phase { kDrive, kSettleAfterLeg, kTurn, kSettleAfterTurn, kDone };
  static constexpr double kArrival_m = 5e-4;
  static constexpr double kMinSpeed_mps = 0.01;
  static constexpr double kApproachGain = 1.0;  // 1/s
  static constexpr double kBrake = 0.7;         // use 70 % of the profile's deceleration
  static constexpr double kHeadingTolerance_rad = 2e-4;
  static constexpr double kMinTurnRate_radps = 0.02;
  static constexpr double kSettle_s = 0.3;

  VelocityCommand enter(Phase phase) {
    phase_ = phase;
    phase_time_s_ = 0.0;
    return {};
  }
  void startLeg() {
    heading_ = wrapAngle(sign_ * 0.5 * kPi * leg_);
    leg_start_ = corner_;
    corner_ = leg_start_ + side_m_ * Vec2(std::cos(heading_), std::sin(heading_));
    // Snap the corners to the exact square (cos(pi/2) is not exactly 0).
    corner_ = corner_.unaryExpr([](double c) { return std::round(c * 1e9) / 1e9; });
    enter(leg_ == 0 ? Phase::kDrive : Phase::kTurn);
  }

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

}  // namespace

std::vector<UmbmarkRun> UmbmarkSimulation::runs() const {
  std::vector<UmbmarkRun> out;
  for (const UmbmarkTrial& t : trials)
    if (t.completed)
      out.push_back({t.direction, t.error_m});
  return out;
}

UmbmarkSimulation runUmbmarkInSimulator(const RobotProfile& physical,
                                        const UmbmarkInjection& injection,
                                        const RobotProfile& believed,
                                        const UmbmarkRunConfig& config) {
  require(physical.drive.type == DriveType::kDifferential &&
              believed.drive.type == DriveType::kDifferential,
          "UMBmark needs a differential drive");
  require(finitePositive(believed.drive.wheel_radius_m) &&
              finitePositive(believed.drive.wheelbase_m) &&
              finitePositive(believed.drive.ticksPerWheelRad()),
          "the believed profile needs wheel radius, wheelbase and encoder conversion > 0");
  require(std::isfinite(injection.wheel_diameter_ratio) && injection.wheel_diameter_ratio >= 0.8 &&
              injection.wheel_diameter_ratio <= 1.25 && std::isfinite(injection.wheelbase_scale) &&
              injection.wheelbase_scale >= 0.8 && injection.wheelbase_scale <= 1.25,
          "injected ratios must be within 0.8..1.25");
  require(std::isfinite(injection.slip_stddev) && injection.slip_stddev >= 0.0 &&
              injection.slip_stddev < 0.1,
          "slip stddev must be in [0, 0.1)");
  require(finitePositive(config.side_m) && config.side_m <= 100.0, "side must be in (0, 100] m");
  require(config.runs_per_direction >= 1 && config.runs_per_direction <= 100,
          "runs per direction must be in 1..100");
  require(finitePositive(config.dt_s) && config.dt_s <= 0.1, "dt must be in (0, 0.1] s");
  require(finitePositive(config.speed_mps) && finitePositive(config.turn_rate_radps),
          "speed and turn rate must be > 0");
  require(finitePositive(config.max_run_s) && config.max_run_s / config.dt_s < 1e7 &&
              finitePositive(config.path_period_s),
          "max run time and path period must be > 0");
  const ProfileOdometry odometry = profileOdometry(believed);
  require(odometry.error.empty(), odometry.error);

  // The physical robot: nominal profile without sensors (they do not move the robot), an empty
  // floor, and the injected errors.
  RobotProfile body = physical;
  body.sonars.clear();
  body.bumpers.clear();
  body.proximity.clear();
  SimConfig sim_config;
  sim_config.dt_s = config.dt_s;
  sim_config.seed = config.seed;
  const double e_d = injection.wheel_diameter_ratio;
  sim_config.odometry.left_scale = 2.0 / (e_d + 1.0);
  sim_config.odometry.right_scale = 2.0 * e_d / (e_d + 1.0);
  sim_config.odometry.wheelbase_scale = injection.wheelbase_scale;
  sim_config.odometry.slip_stddev = injection.slip_stddev;
  WorldMap floor;
  floor.name = "UMBmark floor";
  Simulator sim(std::move(floor), std::move(body), sim_config);

  UmbmarkSimulation result;
  TickOdometry odo(believed, odometry.odometry);
  const auto max_steps = static_cast<std::int64_t>(std::ceil(config.max_run_s / config.dt_s));
  const auto path_every =
      std::max<std::int64_t>(1, std::llround(config.path_period_s / config.dt_s));
  TelemetrySample sample;
  for (int i = 0; i < 2 * config.runs_per_direction; ++i) {
    UmbmarkTrial trial;
    trial.direction =
        i % 2 == 0 ? UmbmarkDirection::kClockwise : UmbmarkDirection::kCounterClockwise;
    sim.resetPose(Pose2{});
    sim.step(sample);  // at rest: reads the encoders the odometry starts from
    odo.reset(sample.left_ticks, sample.right_ticks);
    SquareDriver driver(trial.direction, config.side_m, config.speed_mps, config.turn_rate_radps,
                        physical.limits);
    const double start_s = sim.time_s();
    std::int64_t step = 0;
    for (; step < max_steps && !driver.done(); ++step) {
      sim.setCommand(driver.command(odo.pose(), sample.measured_velocity, config.dt_s));
      sim.step(sample);
      odo.update(sample.left_ticks, sample.right_ticks);
      if (step % path_every == 0) {
        trial.true_path.push_back(sim.truePose().position());
        trial.odometry_path.push_back(odo.pose().position());
      }
    }
    trial.completed = driver.done();
    trial.duration_s = sim.time_s() - start_s;
    trial.true_final = sim.truePose();
    trial.odometry_final = odo.pose();
    trial.true_path.push_back(trial.true_final.position());
    trial.odometry_path.push_back(trial.odometry_final.position());
    trial.error_m = trial.true_final.position() - trial.odometry_final.position();
    if (!trial.completed)
      result.diagnostics.push_back("run " + std::to_string(i + 1) + " (" +
                                   toString(trial.direction) + ") did not finish within " +
                                   std::to_string(config.max_run_s) + " s");
    result.trials.push_back(std::move(trial));
  }
  result.ok = result.diagnostics.empty();
  return result;
}

}  // namespace irgs
