#include "core/calibration/umbmark_run.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/calibration/profile_calibration.hpp"
#include "core/calibration/umbmark_square.hpp"
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
  TickOdometry odo(believed.drive.metresPerTick(), odometry.odometry);
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
    UmbmarkSquareDriver driver(trial.direction, config.side_m, config.speed_mps,
                               config.turn_rate_radps, physical.limits);
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
