#include "app/recording/rerun_engine.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <stdexcept>

#include "comms/link/frame_tap.hpp"
#include "comms/link/link_session.hpp"
#include "comms/mavlink/messages.hpp"
#include "core/estimation/estimator_runner.hpp"

namespace irgs::recording {
namespace {

namespace mav = comms::mavlink;

// How often the progress callback is asked (samples or chunks).
constexpr std::size_t kProgressEvery = 256;

bool keepGoing(const RerunProgress& progress, double fraction) {
  return !progress || progress(std::clamp(fraction, 0.0, 1.0));
}

// Robot time -> recording time, per robot-clock segment (a restart starts a new one).
void alignToRecordingClock(std::vector<DecodedSample>& samples) {
  std::size_t begin = 0;
  while (begin < samples.size()) {
    std::size_t end = begin + 1;
    while (end < samples.size() && samples[end].sample.time_s >= samples[end - 1].sample.time_s)
      ++end;
    double offset = std::numeric_limits<double>::infinity();
    for (std::size_t i = begin; i < end; ++i)
      offset = std::min(offset, samples[i].recording_t_s - samples[i].sample.time_s);
    for (std::size_t i = begin; i < end; ++i)
      samples[i].recording_t_s = samples[i].sample.time_s + offset;
    begin = end;
  }
}

}  // namespace

DecodedRecording decodeRecording(const Recording& recording, const RobotProfile& profile,
                                 const RerunProgress& progress) {
  DecodedRecording out;
  // The live defaults: the recording is of a live session, its times are the live times.
  const comms::LinkSessionConfig session_config;
  mav::FrameDecoder decoder;
  comms::LinkSession session(session_config);
  comms::TelemetryAssembler assembler(profile);
  std::uint8_t robot_system = session_config.target_system;
  std::vector<mav::Frame> frames;

  std::size_t received = 0;
  for (const RecordedFrame& f : recording.frames)
    received += f.dir == static_cast<std::uint8_t>(comms::TapDirection::kReceived) ? 1 : 0;

  auto collect = [&](double t) {
    for (TelemetrySample& s : assembler.takeReady())
      out.samples.push_back({t, std::move(s)});
  };
  // Link::flush: the session's events, delivered after the frame that caused them (a link-up at
  // its heartbeat) and after each timer tick.
  auto flush = [&](double t) {
    for (const comms::LinkEvent& event : session.takeOutput().events) {
      if (event.kind == comms::LinkEventKind::kLinkUp) {
        assembler.reset();  // LinkedRobot::State::onEvent: the robot may have restarted
        ++out.stats.link_ups;
      }
    }
    collect(t);
  };

  bool open = false;
  std::size_t fed = 0;
  for (const RecordedFrame& f : recording.frames) {
    if (f.dir != static_cast<std::uint8_t>(comms::TapDirection::kReceived))
      continue;
    const double t = f.t_s;
    if (!open) {
      session.start(t);
      session.onTransportOpen(t, "recording");
      flush(t);
      open = true;
    }
    // The timers of Link and LinkedRobot, caught up to this chunk's arrival.
    assembler.tick(t);
    collect(t);
    session.tick(t);
    flush(t);

    frames.clear();
    const mav::DecodeCounters counters = decoder.feed(f.bytes, frames);
    out.stats.decoder += counters;
    session.onReceived(f.bytes.size(), counters, t);
    for (const mav::Frame& frame : frames) {
      session.onFrame(frame, t);
      if (session.hasPendingEvents())
        flush(t);
      // LinkedRobot::State::onFrame.
      if (frame.system_id == session_config.system_id)
        continue;
      if (robot_system == 0) {
        const auto hb = frame.as<mav::Heartbeat>();
        if (hb && hb->type != static_cast<std::uint8_t>(mav::MavType::kGcs)) {
          robot_system = frame.system_id;
        } else {
          ++out.stats.other_systems;
          continue;
        }
      }
      if (frame.system_id != robot_system) {
        ++out.stats.other_systems;
        continue;
      }
      if (frame.as<mav::ParamValue>())
        continue;
      assembler.onFrame(frame, t);
      collect(t);
    }
    flush(t);
    ++out.stats.chunks;
    out.stats.bytes += f.bytes.size();
    if (++fed % kProgressEvery == 0 &&
        !keepGoing(progress, static_cast<double>(fed) / static_cast<double>(received))) {
      return {};
    }
  }
  // LinkedRobot::finish: what the assembler still holds is all there is.
  const double end_t = recording.frames.empty() ? 0.0 : recording.frames.back().t_s;
  assembler.reset();
  collect(end_t);
  out.stats.assembler = assembler.counters();
  alignToRecordingClock(out.samples);
  return out;
}

std::optional<RerunRun> runPipeline(const std::vector<DecodedSample>& samples,
                                    const std::vector<RecordedTruth>& truth,
                                    const RerunParameters& parameters, const RobotProfile& profile,
                                    const WorldMap& map, const RerunProgress& progress) {
  RerunRun run;
  run.parameters = parameters;
  run.grid = OccupancyGrid(parameters.grid_resolution_m);  // throws for a bad resolution
  const SonarMapper mapper(profile, parameters.sensor_model, parameters.validDistance());
  std::optional<EstimatorRunner> estimator;
  if (parameters.estimator && !samples.empty()) {
    EstimatorRunnerConfig config = parameters.estimator_config;
    config.kind = *parameters.estimator;
    estimator.emplace(map, profile, samples.front().sample.odometry_pose, config);
  }
  std::vector<TimedPose> truth_track;
  truth_track.reserve(truth.size());
  for (const RecordedTruth& t : truth)
    truth_track.push_back({t.t_s, {t.x_m, t.y_m, t.theta_rad}});

  run.trajectory.reserve(samples.size());
  std::size_t index = 0;
  for (const DecodedSample& decoded : samples) {
    RerunPose pose;
    pose.recording_t_s = decoded.recording_t_s;
    pose.robot_t_s = decoded.sample.time_s;
    pose.odometry = pose.pose = decoded.sample.odometry_pose;
    if (Pose2 t; interpolatePose(truth_track, decoded.recording_t_s, t))
      pose.truth = t;
    SonarMapStats stats;
    if (estimator) {
      TelemetrySample sample = decoded.sample;
      if (pose.truth)
        sample.true_pose = pose.truth;  // the stereo EKF simulates its echoes from the truth
      pose.pose = estimator->feed(sample).estimate;
      if (parameters.map_on_estimate) {
        sample.odometry_pose = pose.pose;
        stats = mapper.integrate(sample, run.grid);
      } else {
        stats = mapper.integrate(decoded.sample, run.grid);
      }
    } else {
      stats = mapper.integrate(decoded.sample, run.grid);
    }
    run.mapping.integrated += stats.integrated;
    run.mapping.skipped += stats.skipped;
    run.trajectory.push_back(pose);
    if (++index % kProgressEvery == 0 &&
        !keepGoing(progress, static_cast<double>(index) / static_cast<double>(samples.size())))
      return std::nullopt;
  }
  (void)run.grid.takeDirtyRect();
  if (!truth_track.empty()) {
    std::vector<TimedPose> poses;
    poses.reserve(run.trajectory.size());
    for (const RerunPose& p : run.trajectory)
      poses.push_back({p.recording_t_s, p.pose});
    TrajectoryDifference error = compareTrajectories(poses, truth_track);
    if (error.compared > 0)
      run.truth_error = error;
  }
  return run;
}

RerunResult rerunRecording(const Recording& recording, const RobotProfile& profile,
                           const WorldMap& map, const RerunParameters& recorded,
                           const RerunParameters& changed, const RerunProgress& progress,
                           const GridCompareOptions& compare) {
  RerunResult result;
  // Shares of the progress bar: decoding, the recorded run, the re-run.
  constexpr double kDecodeShare = 0.2;
  constexpr double kRunShare = 0.4;
  auto stage = [&progress](double base, double share) -> RerunProgress {
    if (!progress)
      return {};
    return [&progress, base, share](double f) { return progress(base + share * f); };
  };
  try {
    if (const auto error = gridCompareOptionsError(compare)) {
      result.error = *error;
      return result;
    }
    if (recording.receivedFrameCount() == 0) {
      result.error =
          "the recording holds no received link bytes (no robot link and no simulator sample in "
          "it, or made before simulator sessions were recorded as frames)";
      return result;
    }
    bool cancelled = false;
    DecodedRecording decoded = decodeRecording(recording, profile, [&](double f) {
      cancelled = !keepGoing(stage(0.0, kDecodeShare), f);
      return !cancelled;
    });
    // Also asked between the stages: a short recording never reaches kProgressEvery.
    if (cancelled || !keepGoing(progress, kDecodeShare)) {
      result.cancelled = true;
      result.error = "cancelled";
      return result;
    }
    result.decode = decoded.stats;
    result.samples = decoded.samples.size();
    if (decoded.samples.empty()) {
      result.error = "the recording's link bytes hold no telemetry samples";
      return result;
    }
    auto first = runPipeline(decoded.samples, recording.truth, recorded, profile, map,
                             stage(kDecodeShare, kRunShare));
    auto second = first && keepGoing(progress, kDecodeShare + kRunShare)
                      ? runPipeline(decoded.samples, recording.truth, changed, profile, map,
                                    stage(kDecodeShare + kRunShare, kRunShare))
                      : std::nullopt;
    if (!first || !second) {
      result.cancelled = true;
      result.error = "cancelled";
      return result;
    }
    result.recorded = std::move(*first);
    result.rerun = std::move(*second);
    result.metrics.grid = compareGrids(result.recorded.grid, result.rerun.grid, compare);
    std::vector<TimedPose> a, b;
    a.reserve(result.rerun.trajectory.size());
    b.reserve(result.recorded.trajectory.size());
    for (const RerunPose& p : result.rerun.trajectory)
      a.push_back({p.recording_t_s, p.pose});
    for (const RerunPose& p : result.recorded.trajectory)
      b.push_back({p.recording_t_s, p.pose});
    result.metrics.pose = compareTrajectories(a, b);
    keepGoing(progress, 1.0);
  } catch (const std::exception& e) {
    result.error = e.what();
  }
  return result;
}

}  // namespace irgs::recording
