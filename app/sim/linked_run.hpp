#pragma once
// `irgs-sim --connect URL`: a headless run against a linked robot instead of the in-process
// simulator: MAVLink, or ARCOS/P2OS when the URL says ?protocol=arcos
// (comms/robot/remote_robot.hpp). Either a drive script runs on the wall clock (the robot's own
// clock runs at wall speed), or a host mission (map building, goal, coverage: core/mission) runs
// through a MissionRunner exactly as it does against the simulator: the robot runs the motion
// primitives it sends, the mission reacts to the samples and reports that come back (late and
// sparse over a real link). Every sample is integrated into the grid by the same SonarMapper as
// the in-process run, so the outputs (writeScenarioOutputs, writeBehaviourOutputs) have the same
// form.
//
// Frames: with `anchor` set, the odometry is re-expressed by the rigid transform that puts the
// first sample at the anchor (the map-frame start pose): an ARCOS robot counts from (0, 0, 0) at
// OPEN, irgs-robot over MAVLink already reports the map frame (the transform is then the
// identity up to the motion before the first sample). A linked robot reports no ground truth:
// the trajectory's truth columns and the final true pose repeat the (anchored) odometry, and the
// odometry error is not measured (NaN, written as null); linkedRunJson() says so for the user.

#include <atomic>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "comms/link/link_types.hpp"
#include "comms/mavlink/signing.hpp"
#include "core/mapping/occupancy_grid.hpp"
#include "core/mission/mission.hpp"
#include "core/robot/robot_profile.hpp"
#include "core/scenario/behaviour_runner.hpp"
#include "core/scenario/scenario_runner.hpp"
#include "core/sim/drive_script.hpp"

namespace irgs::app {

struct LinkedRunSpec {
  std::string url;  // serial:///dev/ttyUSB0?baud=115200, tcp://host:8101?protocol=arcos, ...
  RobotProfile profile;
  DriveScript script;
  // When set, drives the robot instead of the script: it sees every sample and report
  // (anchored) and its requests are sent at once; the run ends when it finishes or after
  // duration_s. Not owned.
  Mission* behaviour = nullptr;
  std::optional<Pose2> anchor;      // map-frame pose of the first sample (see the file comment)
  double duration_s = 60.0;         // wall seconds of driving after the link is up (budget)
  double connect_timeout_s = 10.0;  // link up and first sample, else an error
  // MAVLink signing (--signing-key): every frame sent is signed, only frames signed with the
  // key are accepted. ARCOS has no signing: a key is refused there.
  std::optional<comms::mavlink::SigningKey> signing_key;
  double grid_resolution_m = 0.01;
  double trajectory_period_s = 0.1;  // one trajectory row per period of robot time
  double stop_timeout_s = 2.0;       // wait for the robot to confirm the final stop
  SonarInverseModel sonar_model;
  const std::atomic<bool>* cancel = nullptr;    // set (e.g. by SIGINT) to end the run early
  std::function<void(const std::string&)> log;  // console lines (link events, progress)
  std::function<double()> wall_clock;           // seconds, for the wall_clock_s metric
};

struct LinkedRunResult {
  std::optional<ScenarioResult> result;  // empty when error is set
  BehaviourMetrics behaviour;            // filled when spec.behaviour was set
  std::string error;                     // the link never came up, bad URL, ...
  std::string protocol;                  // "mavlink" or "arcos" (empty: bad URL)
  std::string robot;                     // the adapter's describe() once connected
  bool cancelled = false;                // ended early by `cancel` (outputs are still valid)
  bool stop_acknowledged = false;        // the robot confirmed the final stop
  std::uint64_t samples = 0;
  std::uint64_t dropped_samples = 0;
  std::optional<Pose2> first_odometry;  // the robot's own pose at the first sample
  comms::LinkStats link_stats;
};

// Runs the scenario; blocks for about connect time + duration_s (or until the behaviour
// finishes). Never throws for link or robot problems (they are in error / the log); throws
// std::invalid_argument for a spec with non-positive durations or an invalid profile/sonar model.
LinkedRunResult runLinkedScenario(const LinkedRunSpec& spec);

// The run's extra document (link.json): URL, protocol, link statistics, sample counts, the
// anchoring and the note that truth is not available from a linked robot.
std::string linkedRunJson(const LinkedRunSpec& spec, const LinkedRunResult& result);

}  // namespace irgs::app
