#include "core/estimation/dr_experiment.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/sim/random.hpp"
#include "core/sim/simulator.hpp"
#include "core/world/world_map.hpp"

namespace irgs {

namespace {

// Stream purposes / seed salts (each experiment part draws from its own stream).
constexpr std::uint64_t kRateTableStream = 0x7AB1E;
constexpr std::uint64_t kRestRunSalt = 0x5747;
constexpr std::uint64_t kEncoderErrorStream = 0xE4C0;
constexpr std::uint64_t kCalibrationSalt = 0xCA1B;

void require(bool condition, const std::string& what) {
  if (!condition)
    throw std::invalid_argument(what);
}

WorldMap emptyWorld() {
  WorldMap map;
  map.name = "empty floor";
  map.start = Pose2{0.0, 0.0, 0.0};
  return map;
}

// Waypoint controller on the navigation pose: per leg turn in place to the leg's
// bearing, drive along the leg line (cross-track correction), stop, pause.
class LoopController {
 public:
  LoopController(const DrLoopConfig& c, std::vector<Vec2> targets)
      : config_(c), targets_(std::move(targets)) {
    startLeg();
  }

  bool done() const { return phase_ == Phase::kDone; }

  VelocityCommand command(const Pose2& pose, double dt_s) {
    phase_time_s_ += dt_s;
    switch (phase_) {
      case Phase::kTurn: {
        const double e = wrapAngle(leg_heading_ - pose.theta);
        if (std::abs(e) < 1e-3 && phase_time_s_ > 0.5) {
          enter(Phase::kDrive);
          return {};
        }
        return {0.0, std::clamp(2.0 * e, -config_.turn_rate_radps, config_.turn_rate_radps)};
      }
      case Phase::kDrive: {
        const Vec2 to_goal = targets_[leg_] - pose.position();
        const Vec2 dir(std::cos(leg_heading_), std::sin(leg_heading_));
        const double along = to_goal.dot(dir);
        if (along <= 0.002) {
          enter(Phase::kPause);
          return {};
        }
        const double offset = cross(dir, pose.position() - leg_start_);  // left of the leg > 0
        const double wanted = leg_heading_ + std::atan(-0.5 * offset);
        const double v = std::min(config_.speed_mps, 0.5 * along + 0.01);
        const double w = std::clamp(2.0 * wrapAngle(wanted - pose.theta), -config_.turn_rate_radps,
                                    config_.turn_rate_radps);
        return {v, w};
      }
      case Phase::kPause:
        if (phase_time_s_ >= config_.waypoint_pause_s) {
          if (++leg_ >= targets_.size())
            enter(Phase::kDone);
          else
            startLeg();
        }
        return {};
      case Phase::kDone:
        return {};
    }
    return {};
  }

 private:
  enum class Phase { kTurn, kDrive, kPause, kDone };

  void enter(Phase p) {
    phase_ = p;
    phase_time_s_ = 0.0;
  }
  void startLeg() {
    leg_start_ = leg_ == 0 ? Vec2(0.0, 0.0) : targets_[leg_ - 1];
    const Vec2 d = targets_[leg_] - leg_start_;
    leg_heading_ = std::atan2(d.y(), d.x());
    enter(Phase::kTurn);
  }

  const DrLoopConfig& config_;
  std::vector<Vec2> targets_;
  Phase phase_ = Phase::kTurn;
  double phase_time_s_ = 0.0;
  std::size_t leg_ = 0;
  Vec2 leg_start_ = Vec2::Zero();
  double leg_heading_ = 0.0;
};

}  // namespace

GyroCalibrationRun calibrateSimulatedGyro(const GyroErrorModel& model, std::uint64_t seed,
                                          const GyroCalibrationRunConfig& c) {
  validate(model);
  require(std::isfinite(c.table_min_dps) && std::isfinite(c.table_max_dps) &&
              c.table_min_dps < c.table_max_dps && c.table_step_dps > 0.0 &&
              std::isfinite(c.table_step_dps),
          "calibrateSimulatedGyro: needs table_min < table_max and step > 0");
  require(c.table_dwell_s > 0.0 && c.rest_duration_s > 0.0 && c.dt_s > 0.0 && c.dt_s <= 1.0 &&
              std::isfinite(c.table_dwell_s) && std::isfinite(c.rest_duration_s),
          "calibrateSimulatedGyro: dwell, duration must be > 0 and dt in (0, 1]");
  require((c.table_max_dps - c.table_min_dps) / c.table_step_dps < 1e5 &&
              c.table_dwell_s / c.dt_s < 1e6 && c.rest_duration_s / c.dt_s < 1e7,
          "calibrateSimulatedGyro: run too long");
  require(c.bias_order == 1 || c.bias_order == 2, "calibrateSimulatedGyro: bias_order 1 or 2");
  require(std::isfinite(c.rest_temperature_mid_c) &&
              std::isfinite(c.rest_temperature_amplitude_c) &&
              std::isfinite(c.rest_temperature_period_s) && c.rest_temperature_period_s >= 0.0,
          "calibrateSimulatedGyro: rest temperature cycle must be finite, period >= 0");

  GyroCalibrationRun run;
  // Rate table at constant temperature: the gyro alone on the table (the robot's turn rate
  // limit does not apply).
  GyroErrorModel table_model = model;
  table_model.enabled = true;
  table_model.temperature_start_c = table_model.temperature_end_c = c.table_temperature_c;
  GyroSimulator table(table_model, SimRandom::stream(seed, kRateTableStream));
  const int steps = static_cast<int>(std::llround(c.table_dwell_s / c.dt_s));
  const int rates =
      static_cast<int>(std::floor((c.table_max_dps - c.table_min_dps) / c.table_step_dps + 1e-9));
  double t = 0.0;
  for (int i = 0; i <= rates; ++i) {
    const double rate_dps = c.table_min_dps + c.table_step_dps * i;
    for (int k = 0; k < steps; ++k) {
      t += c.dt_s;
      const GyroReading r = table.read(degToRad(rate_dps), t, c.dt_s);
      if (!r.saturated)
        run.rate_table.push_back({rate_dps, radToDeg(r.rate_radps)});
    }
  }
  // Stationary run in the simulator (robot at rest, temperature cycled).
  SimConfig sim_config;
  sim_config.dt_s = c.dt_s;
  sim_config.seed = splitMix64(seed ^ kRestRunSalt);
  sim_config.gyro = model;
  sim_config.gyro.enabled = true;
  sim_config.gyro.temperature_start_c = sim_config.gyro.temperature_end_c =
      c.rest_temperature_mid_c;
  sim_config.gyro.temperature_cycle_amplitude_c = c.rest_temperature_amplitude_c;
  sim_config.gyro.temperature_cycle_period_s = c.rest_temperature_period_s;
  Simulator sim(emptyWorld(), drLoopRobot(), sim_config);
  TelemetrySample sample;
  const auto rest_steps = static_cast<std::int64_t>(std::llround(c.rest_duration_s / c.dt_s));
  for (std::int64_t k = 0; k < rest_steps; ++k) {
    sim.step(sample);
    if (sample.gyro && !sample.gyro->saturated)
      run.rest.push_back({sample.gyro->temperature_c, radToDeg(sample.gyro->rate_radps)});
  }

  run.scale_fit = fitScaleFactorCurve(run.rate_table);
  run.bias_fit = fitTemperatureBias(run.rest, c.bias_order, run.scale_fit.curve);
  run.calibration.scale = run.scale_fit.curve;
  run.calibration.bias = run.bias_fit.bias;
  return run;
}

RobotProfile drLoopRobot() {
  RobotProfile p;
  p.name = "labmate-like";
  p.description = "Differential drive of 001_… (TRC Labmate-like), encoders and a gyro only";
  p.drive.type = DriveType::kDifferential;
  p.drive.wheel_radius_m = 0.0762;
  p.drive.wheelbase_m = 0.5;
  p.drive.encoder_counts_per_motor_rad = 27.0;
  p.drive.gear_ratio = 100.0;
  p.limits.max_speed_mps = 0.5;
  p.limits.max_turn_rate_radps = 1.0;
  p.limits.max_accel_mps2 = 0.5;
  p.limits.max_turn_accel_radps2 = 1.0;
  return p;
}

std::vector<Vec2> defaultLoopWaypoints() {
  return {{30.0, 0.0}, {36.0, 22.0}, {12.0, 32.0}, {-6.0, 16.0}};
}

DrLoopResult runDrLoop(const DrLoopConfig& c) {
  require(std::isfinite(c.dt_s) && c.dt_s > 0.0 && c.dt_s <= 0.1, "runDrLoop: dt_s in (0, 0.1]");
  require(std::isfinite(c.speed_mps) && c.speed_mps > 0.0 && std::isfinite(c.turn_rate_radps) &&
              c.turn_rate_radps > 0.0,
          "runDrLoop: speed and turn rate must be > 0");
  require(!c.waypoints.empty(), "runDrLoop: needs at least one waypoint");
  for (const Vec2& w : c.waypoints)
    require(std::isfinite(w.x()) && std::isfinite(w.y()), "runDrLoop: non-finite waypoint");
  require(c.initial_rest_s >= 0.0 && c.waypoint_pause_s >= 0.0 && c.trace_period_s > 0.0 &&
              c.max_duration_s > 0.0 && c.max_duration_s / c.dt_s < 1e8,
          "runDrLoop: durations must be >= 0 (trace period, max duration > 0)");
  require(c.encoder_scale_stddev >= 0.0 && c.encoder_scale_stddev < 0.1 &&
              c.wheelbase_error_stddev >= 0.0 && c.wheelbase_error_stddev < 0.1 &&
              c.wheel_slip_stddev >= 0.0,
          "runDrLoop: encoder error stddevs must be in [0, 0.1)");
  validate(c.gyro);

  const RobotProfile robot = drLoopRobot();
  const double wheelbase = robot.drive.wheelbase_m;
  DrLoopResult result;

  // The run's encoder errors (truth).
  SimRandom error_rng = SimRandom::stream(c.seed, kEncoderErrorStream);
  result.true_right_scale_error = c.encoder_scale_stddev * error_rng.gaussian();
  result.true_left_scale_error = c.encoder_scale_stddev * error_rng.gaussian();
  const double wheelbase_scale = 1.0 + c.wheelbase_error_stddev * error_rng.gaussian();
  result.true_wheelbase_error_m = wheelbase * (wheelbase_scale - 1.0);

  const GyroCalibration calibration =
      c.calibration
          ? *c.calibration
          : calibrateSimulatedGyro(c.gyro, splitMix64(c.seed ^ kCalibrationSalt)).calibration;

  SimConfig sim_config;
  sim_config.dt_s = c.dt_s;
  sim_config.seed = c.seed;
  sim_config.odometry.right_scale = 1.0 + result.true_right_scale_error;
  sim_config.odometry.left_scale = 1.0 + result.true_left_scale_error;
  sim_config.odometry.wheelbase_scale = wheelbase_scale;
  sim_config.odometry.slip_stddev = c.wheel_slip_stddev;
  sim_config.gyro = c.gyro;
  sim_config.gyro.enabled = true;
  Simulator sim(emptyWorld(), robot, sim_config);

  EncoderGyroFilterConfig filter_config = c.filter;
  filter_config.wheelbase_m = wheelbase;
  if (c.derive_filter_noise) {
    const GyroErrorModel& g = c.gyro;
    filter_config.encoder_scale_stddev = std::max(c.encoder_scale_stddev, 1e-5);
    filter_config.wheelbase_stddev_m = std::max(c.wheelbase_error_stddev * wheelbase, 1e-5);
    // The calibration run had its own random scale factor: the residual is the difference.
    filter_config.gyro_scale_stddev = std::max(std::sqrt(2.0) * g.scale_factor_stddev, 1e-5);
    const double drift_radps = degToRad(g.bias_instability_dps);
    filter_config.gyro_bias_stddev_radps = std::max(drift_radps, 1e-7);
    filter_config.gyro_bias_variance_rate_rad2_per_s3 =
        std::max(2.0 * drift_radps * drift_radps / g.bias_correlation_time_s, 1e-16);
    const double arw = degToRad(g.angle_random_walk_dps_per_sqrt_s);
    filter_config.gyro_angle_random_walk_rad2_per_s = std::max(arw * arw, 1e-12);
    const double slip_per_m = c.wheel_slip_stddev * c.wheel_slip_stddev * c.speed_mps * c.dt_s;
    filter_config.wheel_travel_variance_per_m = std::max(4.0 * slip_per_m, 1e-9);
  }

  std::vector<Vec2> targets = c.waypoints;
  targets.emplace_back(0.0, 0.0);
  TelemetrySample sample;
  const double metres_per_tick = robot.drive.metresPerTick();
  const auto calibrated = [&](const TelemetrySample& s) -> std::optional<double> {
    if (!s.gyro || s.gyro->saturated)
      return std::nullopt;
    return calibration.compensateRadps(s.gyro->rate_radps, s.gyro->temperature_c);
  };

  // Rest: average the calibrated gyro output to remove the turn-on bias (001 2.6 step 1).
  double bias_sum = 0.0;
  std::int64_t bias_count = 0;
  const auto rest_steps = static_cast<std::int64_t>(std::llround(c.initial_rest_s / c.dt_s));
  for (std::int64_t k = 0; k < rest_steps; ++k) {
    sim.step(sample);
    if (const auto rate = calibrated(sample)) {
      bias_sum += *rate;
      ++bias_count;
    }
  }
  filter_config.initial_gyro_bias_radps =
      bias_count > 0 ? bias_sum / static_cast<double>(bias_count) : 0.0;
  EncoderGyroFilter filter(filter_config, sim.truePose());
  LoopController controller(c, targets);

  std::int64_t last_left = sample.left_ticks, last_right = sample.right_ticks;
  double next_trace_s = sim.time_s();
  Pose2 last_true = sim.truePose();
  double nis_sum = 0.0;
  std::int64_t nis_count = 0;
  const auto max_steps = static_cast<std::int64_t>(std::ceil(c.max_duration_s / c.dt_s));
  for (std::int64_t k = rest_steps; k < max_steps && !controller.done(); ++k) {
    sim.setCommand(controller.command(filter.pose(), c.dt_s));
    sim.step(sample);
    const double dleft = static_cast<double>(sample.left_ticks - last_left) * metres_per_tick;
    const double dright = static_cast<double>(sample.right_ticks - last_right) * metres_per_tick;
    last_left = sample.left_ticks;
    last_right = sample.right_ticks;
    const DrStepResult step = filter.step({dright, dleft, calibrated(sample), c.dt_s});
    if (step.status == DrStepStatus::kUpdated) {
      nis_sum += step.nis;
      ++nis_count;
    }
    result.distance_m += (sim.truePose().position() - last_true.position()).norm();
    last_true = sim.truePose();
    if (sample.time_s + 1e-9 >= next_trace_s) {
      DrTracePoint point;
      point.time_s = sample.time_s;
      point.truth = sim.truePose();
      point.filtered = filter.pose();
      point.unfiltered = filter.unfilteredPose();
      point.sigma = filter.covariance().diagonal().cwiseMax(0.0).cwiseSqrt();
      result.trace.push_back(point);
      next_trace_s += c.trace_period_s;
    }
  }
  result.completed = controller.done();
  result.duration_s = sim.time_s();
  result.true_final = sim.truePose();
  result.filtered_final = filter.pose();
  result.unfiltered_final = filter.unfilteredPose();
  result.final_model = filter.sensorModel();
  result.mode = filter.mode();
  result.fallback = filter.fallbackReason();
  result.updates = filter.updateCount();
  result.gated = filter.gatedCount();
  result.mean_nis = nis_count > 0 ? nis_sum / static_cast<double>(nis_count) : 0.0;
  result.return_to_start_m = result.true_final.position().norm();
  result.filtered_error_m =
      (result.filtered_final.position() - result.true_final.position()).norm();
  result.unfiltered_error_m =
      (result.unfiltered_final.position() - result.true_final.position()).norm();
  result.filtered_heading_error_rad =
      wrapAngle(result.true_final.theta - result.filtered_final.theta);
  result.unfiltered_heading_error_rad =
      wrapAngle(result.true_final.theta - result.unfiltered_final.theta);
  return result;
}

}  // namespace irgs
