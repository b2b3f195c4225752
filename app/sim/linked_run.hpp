#pragma once
// `irgs-sim --connect URL`: the headless scenario run against a robot behind a MAVLink link
// instead of the in-process simulator. The drive script runs on the wall clock (the robot's own
// clock runs at wall speed), its commands go out through LinkedRobot, and the samples that come
// back are integrated into the grid by the same SonarMapper as the in-process run, so the
// outputs (writeScenarioOutputs) have the same form. A linked robot reports no ground truth:
// the trajectory's truth columns and the final true pose repeat the odometry, and the odometry
// error is not measured (NaN, written as null); linkedRunNotes() says so for the user.

#include <atomic>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "comms/link/link_types.hpp"
#include "core/mapping/occupancy_grid.hpp"
#include "core/robot/robot_profile.hpp"
#include "core/scenario/scenario_runner.hpp"
#include "core/sim/drive_script.hpp"

namespace irgs::app {

struct LinkedRunSpec {
  std::string url;  // serial:///dev/ttyUSB0?baud=115200, tcp://host:5760, ...
  RobotProfile profile;
  DriveScript script;
  double duration_s = 60.0;         // wall seconds of driving after the link is up
  double connect_timeout_s = 10.0;  // link up and first sample, else an error
  double grid_resolution_m = 0.01;
  double trajectory_period_s = 0.1;  // one trajectory row per period of robot time
  double stop_timeout_s = 2.0;       // wait for the robot to acknowledge the final stop
  SonarInverseModel sonar_model;
  const std::atomic<bool>* cancel = nullptr;    // set (e.g. by SIGINT) to end the run early
  std::function<void(const std::string&)> log;  // console lines (link events, progress)
};

struct LinkedRunResult {
  std::optional<ScenarioResult> result;  // empty when error is set
  std::string error;                     // the link never came up, bad URL, ...
  bool cancelled = false;                // ended early by `cancel` (outputs are still valid)
  bool stop_acknowledged = false;        // the robot acknowledged IRGS_STOP at the end
  std::uint64_t samples = 0;
  std::uint64_t dropped_samples = 0;
  comms::LinkStats link_stats;
};

// Runs the scenario; blocks for about connect time + duration_s. Never throws for link or robot
// problems (they are in error / the log); throws std::invalid_argument for a spec with
// non-positive durations or an invalid profile/sonar model.
LinkedRunResult runLinkedScenario(const LinkedRunSpec& spec);

// The run's extra document (link.json): URL, link statistics, sample counts and the note that
// truth is not available from a linked robot.
std::string linkedRunJson(const LinkedRunSpec& spec, const LinkedRunResult& result);

}  // namespace irgs::app
