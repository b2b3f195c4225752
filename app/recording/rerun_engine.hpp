#pragma once
// Re-run of a recording with changed parameters (issue 6 item 3, docs/gui.md "Re-run with
// parameters"). The recording's received link bytes are decoded through the same path a live
// link uses — FrameDecoder, LinkSession (link up resets the assembler, as Link/LinkedRobot do),
// the robot-system filter of LinkedRobot and TelemetryAssembler — into the session's telemetry
// samples, as fast as the machine goes (no clock: the recorded times are passed as `now`).
// Those samples then run through the mapper (SonarMapper into an OccupancyGrid) and, when one is
// chosen, an estimator (EstimatorRunner) twice: once with the recorded parameters, which
// reproduces the recorded session's map and trajectory, and once with the changed ones. The
// comparison: grid agreement and occupied F1 (core/mapping/grid_compare.hpp), pose difference
// (core/estimation/trajectory_compare.hpp) and, when the recording holds simulator truth, each
// run's error against it.
//
// Pure apart from the inputs: no Qt, no threads; the GUI runs it on a worker thread, the
// progress callback may cancel it.

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "app/recording/recording_format.hpp"
#include "app/recording/rerun_parameters.hpp"
#include "comms/mavlink/frame_decoder.hpp"
#include "comms/robot/telemetry_assembler.hpp"
#include "core/estimation/trajectory_compare.hpp"
#include "core/mapping/grid_compare.hpp"
#include "core/mapping/occupancy_grid.hpp"
#include "core/mapping/sonar_mapper.hpp"
#include "core/robot/robot_profile.hpp"
#include "core/world/world_map.hpp"

namespace irgs::recording {

// One telemetry sample as the session received it, with its time on the recording's clock: the
// robot's time plus the smallest (recording time of release - robot time) of its robot-clock
// segment (the least delayed arrival), so samples line up with the recording's truth rows. A
// sample is released when its last part has arrived (or the next step began), so the clock is
// late by the least such delay, at most a telemetry period.
struct DecodedSample {
  double recording_t_s = 0.0;
  TelemetrySample sample;
};

struct DecodeStats {
  std::uint64_t chunks = 0;  // received rows fed
  std::uint64_t bytes = 0;
  comms::mavlink::DecodeCounters decoder;
  comms::TelemetryAssemblerCounters assembler;
  std::uint64_t link_ups = 0;       // each resets the assembler, as live
  std::uint64_t other_systems = 0;  // frames of systems other than the robot (ignored)
};

struct DecodedRecording {
  std::vector<DecodedSample> samples;
  DecodeStats stats;
};

// Returns false from the callback to cancel; fraction in [0, 1].
using RerunProgress = std::function<bool(double fraction)>;

// Decodes the received bytes into samples (see the file comment). Empty when cancelled.
DecodedRecording decodeRecording(const Recording& recording, const RobotProfile& profile,
                                 const RerunProgress& progress = {});

struct RerunPose {
  double recording_t_s = 0.0;
  double robot_t_s = 0.0;
  Pose2 odometry;              // what the robot reported
  Pose2 pose;                  // the run's pose: the estimate, or the odometry without one
  std::optional<Pose2> truth;  // recorded truth interpolated at recording_t_s
};

struct RerunRun {
  RerunParameters parameters;
  OccupancyGrid grid;
  std::vector<RerunPose> trajectory;
  SonarMapStats mapping;  // summed over the samples
  // pose - truth, when the recording holds truth over the run's times.
  std::optional<TrajectoryDifference> truth_error;
};

struct RerunMetrics {
  GridComparison grid;        // reference = recorded run, candidate = re-run
  TrajectoryDifference pose;  // re-run pose - recorded pose at the recorded times
};

struct RerunResult {
  std::string error;  // set when nothing could be run (no samples, bad parameters); or cancelled
  bool cancelled = false;
  DecodeStats decode;
  std::size_t samples = 0;
  RerunRun recorded;
  RerunRun rerun;
  RerunMetrics metrics;
};

// Runs the mapper and the estimator with `parameters` over decoded samples. `map` feeds the
// estimator's localization map (the stereo EKF; may be empty). The estimator starts at the first
// sample's odometry pose. Throws std::invalid_argument for parameters the mapper, grid or
// estimator reject. nullopt when cancelled.
std::optional<RerunRun> runPipeline(const std::vector<DecodedSample>& samples,
                                    const std::vector<RecordedTruth>& truth,
                                    const RerunParameters& parameters, const RobotProfile& profile,
                                    const WorldMap& map, const RerunProgress& progress = {});

// decodeRecording + runPipeline(recorded) + runPipeline(changed) + the metrics. Never throws for
// bad input: the reason is in error.
RerunResult rerunRecording(const Recording& recording, const RobotProfile& profile,
                           const WorldMap& map, const RerunParameters& recorded,
                           const RerunParameters& changed, const RerunProgress& progress = {},
                           const GridCompareOptions& compare = {});

}  // namespace irgs::recording
