#pragma once
// irgs-sim --behaviour: runs a host mission and writes its outputs (see simUsage): mapbuild
// (autonomous sonar map building), goal (A* + path amendment + traveling to --goal) and coverage
// (spiral cleaning path + traveling). The robot runs the motion primitives, the host the rest
// (core/mission). The robot is the in-process simulator (runBehaviourMode) or a linked robot
// (app/sim/linked_run.hpp); both set the mission up with prepareBehaviourJob and write the same
// files with writeBehaviourOutputs.

#include <filesystem>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "app/sim/sim_options.hpp"
#include "core/mission/map_building_mission.hpp"
#include "core/mission/mission.hpp"
#include "core/planning/planning_grid.hpp"
#include "core/robot/robot_profile.hpp"
#include "core/scenario/behaviour_runner.hpp"
#include "core/world/world_map.hpp"

namespace irgs::app {

struct BehaviourRunOutcome {
  int exit_code = 0;    // 0 success, 1 a file could not be written, 3 the behaviour failed
  std::string summary;  // one line for the console
  std::vector<std::filesystem::path> written;
  std::string error;
};

// A mission set up for a run, with what its outputs need afterwards.
struct BehaviourJob {
  std::string kind;  // options.behaviour: mapbuild, goal or coverage
  std::unique_ptr<Mission> mission;
  MapBuildingMission* builder = nullptr;  // mapbuild: the mission, for its grid and indices
  Pose2 start;                            // map frame
  std::vector<Vec2> planned;              // goal/coverage: the turning points to travel
  PlanningGrid plan_grid;                 // goal/coverage: the inflated true map
  double lane_m = 0.0;                    // coverage: lane width
  nlohmann::json extra = nlohmann::json::object();  // plan summary for metrics.json
};

// Sets up options.behaviour starting at `start`. goal and coverage plan on `map` (the true map);
// mapbuild needs no map (null: a linked robot in an unknown room). Expected failures (no map
// to plan on, start or goal blocked, no path) come back as an error message; never throws.
std::optional<std::string> prepareBehaviourJob(const SimOptions& options, const WorldMap* map,
                                               const RobotProfile& profile, const Pose2& start,
                                               BehaviourJob& job);

// What the run needs to know for writing its outputs.
struct BehaviourOutputInfo {
  ScenarioRunInfo run;
  const WorldMap* truth = nullptr;  // scores the built map when set (map_score)
  const char* clock = "simulated";  // what duration_s counts, for the summary line
  // Extra documents to write beside the usual outputs (file name, text), e.g. link.json.
  std::vector<std::pair<std::string, std::string>> extra_files;
  nlohmann::json extra = nlohmann::json::object();  // more top-level keys for metrics.json
};

// Scores and writes what a finished run produced: grid.pgm/.yaml/.png (mapbuild: the map the
// behaviour built, on its revised poses), trajectory.csv, metrics.json (behaviour phases, turns,
// map_score against `info.truth`, map_agreement against options.compare, plan or coverage),
// indices.csv or plan.csv and info.extra_files. Fills exit_code, summary and written.
BehaviourRunOutcome writeBehaviourOutputs(const SimOptions& options, BehaviourJob& job,
                                          BehaviourScenarioResult& result,
                                          BehaviourOutputInfo info);

// The in-process run: prepareBehaviourJob + runMissionScenario + writeBehaviourOutputs.
// `clock` gives wall seconds for the wall_clock_s metric. Throws nothing for expected failures:
// a goal that cannot be planned or a behaviour that fails is reported in the outcome (and in
// metrics.json when the outputs could be written).
BehaviourRunOutcome runBehaviourMode(const SimOptions& options, const WorldMap& map,
                                     const RobotProfile& profile,
                                     const std::function<double()>& clock);

}  // namespace irgs::app
