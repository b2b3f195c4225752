#pragma once
// A headless mission run: the in-process simulated robot (SimulatedRobot, which runs motion
// primitives itself) steps once at a time, every sample and primitive report goes to the
// mission through a MissionRunner (and every sample to the live sonar grid, as in
// runScenario), and the mission's requests apply from the next step: the host reacts with no
// delay. Runs until the mission finishes or the time budget ends. Same outputs as runScenario
// plus the mission's phases with their times and counts of on-the-spot turns. A velocity-level
// Behaviour runs as a BehaviourMission.

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/behaviour/behaviour.hpp"
#include "core/mission/mission.hpp"
#include "core/scenario/scenario_outputs.hpp"
#include "core/scenario/scenario_runner.hpp"

namespace irgs {

struct BehaviourScenarioSpec {
  WorldMap map;
  RobotProfile profile;
  std::optional<Pose2> start;  // default: the map's start pose
  SimConfig sim;
  double max_duration_s = 3600.0;  // simulated-time budget; the run stops when it is used up
  double grid_resolution_m = 0.01;
  SonarInverseModel sonar_model;
  double trajectory_period_s = 0.1;
  // Wall clock in seconds for the wall_clock_s metric (core owns no clock); null gives 0.
  std::function<double()> wall_clock;
  // Called after each step with the sample and the mission (GUI progress, tests); may be null.
  std::function<void(const TelemetrySample&, const Mission&)> observer;
  // Called after each step with the simulator (ground-truth probes such as clearance); may be
  // null.
  std::function<void(const Simulator&)> simulator_probe;
};

struct PhaseSpan {
  std::string phase;
  double start_s = 0.0;
  double end_s = 0.0;
};

struct BehaviourMetrics {
  std::string behaviour;
  std::vector<PhaseSpan> phases;  // consecutive, as status().phase changed
  int turns = 0;                  // on-the-spot turns (command v = 0, omega != 0) started
  int primitives = 0;             // motion primitives the mission started
  bool finished = false;
  bool failed = false;  // also true when the time budget ran out before the behaviour finished
  std::string message;
  double wall_clock_s = 0.0;
};

struct BehaviourScenarioResult {
  ScenarioResult scenario;  // grid (from odometry), trajectory and the motion metrics
  BehaviourMetrics behaviour;
};

// Throws what Simulator throws for a spec it cannot run, and std::invalid_argument for a
// non-positive or non-finite max_duration_s.
BehaviourScenarioResult runMissionScenario(const BehaviourScenarioSpec& spec, Mission& mission);
// runMissionScenario with the behaviour as a BehaviourMission.
BehaviourScenarioResult runBehaviourScenario(const BehaviourScenarioSpec& spec,
                                             Behaviour& behaviour);

// metrics.json for a behaviour run: the scenario metrics plus a "behaviour" object.
// `extra` keys (e.g. map scores, coverage %) are added at the top level.
std::string behaviourMetricsJson(const BehaviourScenarioResult& result, const ScenarioRunInfo& info,
                                 const nlohmann::json& extra = nlohmann::json::object());

}  // namespace irgs
