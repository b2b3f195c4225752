#pragma once
// irgs-sim --behaviour: runs a host behaviour against the in-process simulator and writes its
// outputs (see simUsage): mapbuild (autonomous sonar map building), goal (A* + path amendment
// + traveling to --goal) and coverage (spiral cleaning path + traveling).

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "app/sim/sim_options.hpp"
#include "core/robot/robot_profile.hpp"
#include "core/world/world_map.hpp"

namespace irgs::app {

struct BehaviourRunOutcome {
  int exit_code = 0;    // 0 success, 1 a file could not be written, 3 the behaviour failed
  std::string summary;  // one line for the console
  std::vector<std::filesystem::path> written;
  std::string error;
};

// `clock` gives wall seconds for the wall_clock_s metric. Throws nothing for expected failures:
// a goal that cannot be planned or a behaviour that fails is reported in the outcome (and in
// metrics.json when the outputs could be written).
BehaviourRunOutcome runBehaviourMode(const SimOptions& options, const WorldMap& map,
                                     const RobotProfile& profile,
                                     const std::function<double()>& clock);

}  // namespace irgs::app
