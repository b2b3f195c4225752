#include "core/scenario/scenario_runner.hpp"

#include <algorithm>
#include <bit>
#include <cmath>

#include "core/mapping/sonar_mapper.hpp"

namespace irgs {

ScenarioResult runScenario(const ScenarioSpec& spec) {
  WorldMap map = spec.map;
  const Pose2 start = spec.start.value_or(map.start);
  Simulator sim(std::move(map), spec.profile, spec.sim);
  sim.resetPose(start);

  const SonarMapper mapper(spec.profile, spec.sonar_model);
  ScenarioResult result{OccupancyGrid(spec.grid_resolution_m), {}, {}};
  ScenarioMetrics& m = result.metrics;

  const double dt = spec.sim.dt_s;
  // Integer step counts keep the run length exact: no drift from summing dt.
  const auto total_steps = static_cast<std::uint64_t>(std::llround(spec.duration_s / dt));
  const auto rows_every = std::max<std::uint64_t>(
      1, static_cast<std::uint64_t>(std::llround(spec.trajectory_period_s / dt)));

  auto record = [&](double time_s, const VelocityCommand& command, std::uint32_t bumpers) {
    result.trajectory.push_back({time_s, sim.truePose(), sim.odometryPose(), command, bumpers});
  };
  record(0.0, {}, 0);

  std::uint32_t previous_bumpers = 0;
  Pose2 previous_truth = sim.truePose();
  for (std::uint64_t step = 1; step <= total_steps; ++step) {
    const double command_time = static_cast<double>(step - 1) * dt;
    const VelocityCommand command = spec.script.commandAt(command_time);
    sim.setCommand(command);
    const TelemetrySample sample = sim.step();

    mapper.integrate(sample, result.grid);
    for (const SonarReading& reading : sample.sonar) {
      ++m.sonar_readings;
      if (reading.echo)
        ++m.sonar_echoes;
    }
    m.bumper_events +=
        static_cast<std::uint64_t>(std::popcount(sample.bumpers & ~previous_bumpers));
    previous_bumpers = sample.bumpers;

    const Pose2& truth = sim.truePose();
    m.distance_travelled_m += (truth.position() - previous_truth.position()).norm();
    m.rotation_travelled_rad += std::abs(wrapAngle(truth.theta - previous_truth.theta));
    previous_truth = truth;

    if (step % rows_every == 0 || step == total_steps)
      record(sample.time_s, command, sample.bumpers);
  }

  m.steps = total_steps;
  m.duration_s = static_cast<double>(total_steps) * dt;
  m.final_truth = sim.truePose();
  m.final_odometry = sim.odometryPose();
  m.odometry_position_error_m = (m.final_truth.position() - m.final_odometry.position()).norm();
  m.odometry_heading_error_rad = wrapAngle(m.final_odometry.theta - m.final_truth.theta);
  m.explored_area_m2 = result.grid.exploredArea_m2();
  return result;
}

}  // namespace irgs
