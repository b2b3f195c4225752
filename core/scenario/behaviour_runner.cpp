#include "core/scenario/behaviour_runner.hpp"

#include <bit>
#include <cmath>
#include <stdexcept>

#include "core/mapping/sonar_mapper.hpp"
#include "core/mission/behaviour_mission.hpp"
#include "core/mission/mission_runner.hpp"
#include "core/sim/simulated_robot.hpp"

namespace irgs {
namespace {

double rounded(double v, int digits) {
  const double f = std::pow(10.0, digits);
  return std::round(v * f) / f;
}

}  // namespace

BehaviourScenarioResult runMissionScenario(const BehaviourScenarioSpec& spec, Mission& mission) {
  if (!std::isfinite(spec.max_duration_s) || spec.max_duration_s <= 0.0)
    throw std::invalid_argument("max_duration_s must be finite and > 0");
  const double wall_start = spec.wall_clock ? spec.wall_clock() : 0.0;
  SimulatedRobot robot(spec.map, spec.profile, spec.sim);
  Simulator& sim = robot.simulator();
  sim.resetPose(spec.start.value_or(spec.map.start));

  const SonarMapper mapper(spec.profile, spec.sonar_model);
  BehaviourScenarioResult out{{OccupancyGrid(spec.grid_resolution_m), {}, {}}, {}};
  ScenarioResult& result = out.scenario;
  ScenarioMetrics& m = result.metrics;
  BehaviourMetrics& b = out.behaviour;
  b.behaviour = std::string(mission.name());

  MissionRunner runner;
  if (auto refused = runner.start(mission, robot))
    throw std::invalid_argument(*refused);
  const double dt = spec.sim.dt_s;
  const auto total_steps = static_cast<std::uint64_t>(std::llround(spec.max_duration_s / dt));
  const auto rows_every = std::max<std::uint64_t>(
      1, static_cast<std::uint64_t>(std::llround(spec.trajectory_period_s / dt)));

  result.trajectory.push_back({0.0, sim.truePose(), sim.odometryPose(), sim.command(), 0});
  std::uint32_t previous_bumpers = 0;
  Pose2 previous_truth = sim.truePose();
  bool was_turning = false;
  std::uint64_t step = 0;
  bool finished = !runner.running();
  while (step < total_steps && !finished) {
    ++step;
    robot.singleStep();
    const std::vector<TelemetrySample> samples = robot.update(0.0);
    const TelemetrySample& sample = samples.back();
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

    runner.feed(samples);
    // The command the next step runs: the primitive's (stepped at the start of the next step on
    // this sample) or the mission's velocity.
    const VelocityCommand& command = sim.command();
    const bool turning = command.linear_mps == 0.0 && command.angular_radps != 0.0;
    if (turning && !was_turning)
      ++b.turns;
    was_turning = turning;

    const BehaviourStatus status = runner.status();
    if (b.phases.empty() || b.phases.back().phase != status.phase)
      b.phases.push_back({status.phase, sample.time_s, sample.time_s});
    b.phases.back().end_s = sample.time_s;
    if (spec.observer)
      spec.observer(sample, mission);
    if (spec.simulator_probe)
      spec.simulator_probe(sim);

    finished = !runner.running();
    if (step % rows_every == 0 || finished)
      result.trajectory.push_back(
          {sample.time_s, sim.truePose(), sim.odometryPose(), command, sample.bumpers});
  }
  const BehaviourStatus status = runner.status();
  b.primitives = runner.primitivesStarted();
  if (finished) {
    b.finished = true;
    b.failed = status.failed;
    b.message = status.message;
  } else {
    b.failed = true;
    b.message = "time budget of " + std::to_string(spec.max_duration_s) +
                " s used up before the behaviour finished (" + status.phase + ")";
  }

  m.steps = step;
  m.duration_s = static_cast<double>(step) * dt;
  m.final_truth = sim.truePose();
  m.final_odometry = sim.odometryPose();
  m.odometry_position_error_m = (m.final_truth.position() - m.final_odometry.position()).norm();
  m.odometry_heading_error_rad = wrapAngle(m.final_odometry.theta - m.final_truth.theta);
  m.explored_area_m2 = result.grid.exploredArea_m2();
  b.wall_clock_s = spec.wall_clock ? spec.wall_clock() - wall_start : 0.0;
  return out;
}

BehaviourScenarioResult runBehaviourScenario(const BehaviourScenarioSpec& spec,
                                             Behaviour& behaviour) {
  BehaviourMission mission(behaviour);
  return runMissionScenario(spec, mission);
}

std::string behaviourMetricsJson(const BehaviourScenarioResult& result, const ScenarioRunInfo& info,
                                 const nlohmann::json& extra) {
  nlohmann::ordered_json doc =
      nlohmann::ordered_json::parse(metricsJson(result.scenario.metrics, info));
  const BehaviourMetrics& b = result.behaviour;
  nlohmann::ordered_json beh;
  beh["name"] = b.behaviour;
  beh["finished"] = b.finished;
  beh["failed"] = b.failed;
  beh["message"] = b.message;
  beh["turns"] = b.turns;
  beh["primitives"] = b.primitives;
  beh["wall_clock_s"] = rounded(b.wall_clock_s, 3);
  nlohmann::ordered_json phases = nlohmann::ordered_json::array();
  for (const PhaseSpan& p : b.phases)
    phases.push_back(
        {{"phase", p.phase}, {"start_s", rounded(p.start_s, 3)}, {"end_s", rounded(p.end_s, 3)}});
  beh["phases"] = phases;
  doc["behaviour"] = beh;
  for (const auto& [key, value] : extra.items())
    doc[key] = value;
  return doc.dump(2) + "\n";
}

}  // namespace irgs
