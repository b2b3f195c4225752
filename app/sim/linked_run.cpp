#include "app/sim/linked_run.hpp"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <thread>

#include <nlohmann/json.hpp>

#include "comms/robot/remote_robot.hpp"
#include "comms/transport/io_thread.hpp"
#include "core/mapping/sonar_mapper.hpp"
#include "core/mission/mission_runner.hpp"
#include "core/robot/anchored_robot.hpp"

namespace irgs::app {

namespace {

using Clock = std::chrono::steady_clock;
// A script holds each command for a while: drain like the GUI (60 Hz). A mission reacts to
// samples and reports; its requests should reach the robot with the least added delay: poll
// faster.
constexpr auto kScriptLoopPeriod = std::chrono::milliseconds(16);
constexpr auto kBehaviourLoopPeriod = std::chrono::milliseconds(4);

double secondsSince(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

std::string seconds(double s) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f", s);
  return text;
}

bool positive(double v) {
  return std::isfinite(v) && v > 0.0;
}

nlohmann::ordered_json poseJson(const Pose2& p) {
  return {{"x", p.x}, {"y", p.y}, {"theta_deg", radToDeg(p.theta)}};
}

}  // namespace

LinkedRunResult runLinkedScenario(const LinkedRunSpec& spec) {
  if (!positive(spec.duration_s) || !positive(spec.connect_timeout_s) ||
      !positive(spec.grid_resolution_m) || !positive(spec.trajectory_period_s) ||
      !positive(spec.stop_timeout_s))
    throw std::invalid_argument("runLinkedScenario: durations and resolution must be > 0");
  const SonarMapper mapper(spec.profile, spec.sonar_model);  // throws for a bad profile/model

  LinkedRunResult out;
  auto log = [&](const std::string& line) {
    if (spec.log)
      spec.log(line);
  };
  auto cancelled = [&] { return spec.cancel != nullptr && spec.cancel->load(); };
  const double wall_start = spec.wall_clock ? spec.wall_clock() : 0.0;

  const auto url = comms::parseLinkUrl(spec.url);
  if (!url.url) {
    out.error = "bad --connect URL '" + spec.url + "': " + url.error;
    return out;
  }
  comms::IoThread io;
  comms::RemoteRobotConfig config;
  config.mavlink.link.signing_key = spec.signing_key;
  config.mavlink.link.require_signed = spec.signing_key.has_value();
  auto opened = comms::openRemoteRobot(io, *url.url, spec.profile, std::move(config));
  if (!opened.robot) {
    out.error = "cannot open " + spec.url + ": " + opened.error;
    return out;
  }
  comms::RemoteRobot& robot = *opened.robot;
  // Drains the samples that arrived, oldest first (the stop confirmation looks at them).
  auto update = [&robot] { return robot.update(0.0); };
  out.protocol = std::string(robot.protocol());
  std::string last_event;
  auto drainEvents = [&] {
    for (const auto& e : robot.takeEvents()) {
      last_event = e.text;
      log(std::string(comms::toString(e.kind)) + ": " + e.text);
    }
  };

  // 1. Wait for the link and a first sample (the pose the run starts from).
  std::vector<TelemetrySample> pending;
  const Clock::time_point connect_start = Clock::now();
  while (!cancelled()) {
    drainEvents();
    for (auto& s : update())
      pending.push_back(std::move(s));
    if (robot.linkState() == comms::LinkState::kConnected && !pending.empty())
      break;
    if (secondsSince(connect_start) > spec.connect_timeout_s) {
      const bool arcos = out.protocol == "arcos";
      out.error = robot.linkState() == comms::LinkState::kConnected
                      ? "the robot at " + spec.url + " is connected but sent no odometry within " +
                            seconds(spec.connect_timeout_s) + " s"
                      : std::string(arcos ? "no ARCOS robot answered (SYNC/SIP) at "
                                          : "no robot heartbeat from ") +
                            spec.url + " within " + seconds(spec.connect_timeout_s) + " s" +
                            (last_event.empty() ? "" : " (last: " + last_event + ")");
      out.link_stats = robot.linkStats();
      return out;
    }
    std::this_thread::sleep_for(kScriptLoopPeriod);
  }
  if (cancelled() && pending.empty()) {
    out.error = "interrupted before the robot was connected";
    out.cancelled = true;
    return out;
  }
  out.robot = robot.describe();
  log("connected to " + out.robot + ": " +
      (spec.behaviour ? "running " + std::string(spec.behaviour->name()) + " (budget " +
                            seconds(spec.duration_s) + " s)"
                      : "running the script for " + seconds(spec.duration_s) + " s"));

  // Map frame <- the robot's odometry frame: the first sample is put at the anchor; samples and
  // reports come out in the map frame, primitives go in in the robot's frame.
  out.first_odometry = pending.front().odometry_pose;
  AnchoredRobot anchored(robot, spec.anchor);
  pending = anchored.toMap(std::move(pending));
  MissionRunner runner;
  if (spec.behaviour) {
    if (auto refused = runner.start(*spec.behaviour, anchored)) {
      out.error = *refused;
      return out;
    }
  }

  // 2. Drive (script on the wall clock, or the behaviour on every sample); integrate samples.
  ScenarioResult result{OccupancyGrid(spec.grid_resolution_m), {}, {}};
  ScenarioMetrics& m = result.metrics;
  BehaviourMetrics& b = out.behaviour;
  if (spec.behaviour)
    b.behaviour = std::string(spec.behaviour->name());
  std::optional<double> first_time_s;
  std::optional<double> next_row_s;
  std::optional<Pose2> previous_pose;
  std::uint32_t previous_bumpers = 0;
  VelocityCommand command;
  TrajectoryRow last_row;
  // Returns the robot time of the sample relative to the first one.
  auto integrate = [&](const TelemetrySample& s) {
    ++out.samples;
    if (!first_time_s) {
      first_time_s = s.time_s;
      next_row_s = s.time_s;
    }
    mapper.integrate(s, result.grid);
    for (const SonarReading& r : s.sonar) {
      ++m.sonar_readings;
      m.sonar_echoes += r.echo ? 1u : 0u;
    }
    m.bumper_events += static_cast<std::uint64_t>(std::popcount(s.bumpers & ~previous_bumpers));
    previous_bumpers = s.bumpers;
    if (previous_pose) {
      m.distance_travelled_m += (s.odometry_pose.position() - previous_pose->position()).norm();
      m.rotation_travelled_rad += std::abs(wrapAngle(s.odometry_pose.theta - previous_pose->theta));
    }
    previous_pose = s.odometry_pose;
    // A time stamp earlier than the first one: the robot restarted; keep the row clock monotonic.
    const double t = std::max(0.0, s.time_s - *first_time_s);
    last_row = {t, s.odometry_pose, s.odometry_pose, command, s.bumpers};
    if (s.time_s + 1e-9 >= *next_row_s) {
      result.trajectory.push_back(last_row);
      while (*next_row_s <= s.time_s + 1e-9)
        *next_row_s += spec.trajectory_period_s;
    }
    return t;
  };
  // The mission's view of the samples (and the reports that came with them), with the same
  // bookkeeping as runMissionScenario.
  auto consult = [&](const std::vector<TelemetrySample>& samples) {
    if (samples.empty() && !runner.running())
      return;
    runner.feed(samples);
    const double t = last_row.time_s;
    const BehaviourStatus status = runner.status();
    if (b.phases.empty() || b.phases.back().phase != status.phase)
      b.phases.push_back({status.phase, t, t});
    b.phases.back().end_s = t;
    if (!runner.running() && !b.finished) {
      b.finished = true;
      b.failed = status.failed;
      b.message = status.message;
      b.primitives = runner.primitivesStarted();
    }
  };
  auto take = [&](std::vector<TelemetrySample> raw) {
    std::vector<TelemetrySample> samples = anchored.toMap(std::move(raw));
    for (const TelemetrySample& s : samples)
      integrate(s);
    if (spec.behaviour && !b.finished)
      consult(samples);
  };
  for (const auto& s : pending)
    integrate(s);
  if (spec.behaviour)
    consult(pending);
  pending.clear();

  const Clock::time_point run_start = Clock::now();
  const auto period = spec.behaviour ? kBehaviourLoopPeriod : kScriptLoopPeriod;
  bool was_connected = true;
  std::string last_phase = b.phases.empty() ? "" : b.phases.back().phase;
  while (!cancelled() && !b.finished) {
    const double elapsed = secondsSince(run_start);
    if (elapsed >= spec.duration_s)
      break;
    if (!spec.behaviour) {
      command = spec.script.commandAt(elapsed);
      robot.drive(command);  // sent when it changes; the adapter repeats it while non-zero
    }
    take(update());
    if (spec.behaviour) {
      if (!b.phases.empty() && b.phases.back().phase != last_phase) {
        last_phase = b.phases.back().phase;
        log("phase: " + last_phase + " at " + seconds(b.phases.back().start_s) + " s");
      }
    }
    drainEvents();
    const bool connected = robot.linkState() == comms::LinkState::kConnected;
    if (connected && !was_connected)
      log(std::string("link back: the ") + (spec.behaviour ? "behaviour" : "script") +
          " continues at " + seconds(elapsed) + " s");
    was_connected = connected;
    std::this_thread::sleep_for(period);
  }
  out.cancelled = cancelled();
  if (spec.behaviour && !b.finished) {
    b.failed = true;
    b.primitives = runner.primitivesStarted();
    b.message = out.cancelled ? "interrupted (" + spec.behaviour->status().phase + ")"
                              : "time budget of " + seconds(spec.duration_s) +
                                    " s used up before the behaviour finished (" +
                                    spec.behaviour->status().phase + ")";
    runner.abort(b.message);
  }

  // 3. Stop the robot and wait (bounded) for the confirmation and the last samples.
  command = {};
  robot.requestConfirmedStop();
  const Clock::time_point stop_start = Clock::now();
  while (!robot.stopConfirmed() && secondsSince(stop_start) < spec.stop_timeout_s) {
    take(update());
    drainEvents();
    std::this_thread::sleep_for(kScriptLoopPeriod);
  }
  out.stop_acknowledged = robot.stopConfirmed().value_or(false);
  if (!out.stop_acknowledged)
    log("warning: the robot did not confirm the final stop (its own watchdog stops it)");
  take(update());
  drainEvents();
  if (out.samples > 0 &&
      (result.trajectory.empty() || result.trajectory.back().time_s != last_row.time_s))
    result.trajectory.push_back(last_row);

  m.steps = out.samples;
  m.duration_s = result.trajectory.empty() ? 0.0 : result.trajectory.back().time_s;
  if (previous_pose) {
    m.final_truth = m.final_odometry = *previous_pose;
  }
  // No ground truth from a real robot: the odometry error is not measured (null in the JSON).
  m.odometry_position_error_m = std::numeric_limits<double>::quiet_NaN();
  m.odometry_heading_error_rad = std::numeric_limits<double>::quiet_NaN();
  m.explored_area_m2 = result.grid.exploredArea_m2();
  b.wall_clock_s = spec.wall_clock ? spec.wall_clock() - wall_start : 0.0;
  out.dropped_samples = robot.droppedSamples();
  out.link_stats = robot.linkStats();
  out.result = std::move(result);
  return out;
}

std::string linkedRunJson(const LinkedRunSpec& spec, const LinkedRunResult& r) {
  nlohmann::ordered_json doc;
  doc["url"] = spec.url;
  doc["protocol"] = r.protocol;
  doc["robot"] = r.robot;
  doc["truth"] =
      "not available from a linked robot: trajectory.csv true_* columns and final_true_pose "
      "repeat the odometry, odometry_error is not measured (null), grid.png shows one path";
  if (spec.anchor && r.first_odometry) {
    doc["anchor"] = {{"map_start", poseJson(*spec.anchor)},
                     {"robot_first_odometry", poseJson(*r.first_odometry)},
                     {"note", "odometry re-expressed so that the first sample lies at map_start"}};
  } else {
    doc["anchor"] = nullptr;
  }
  doc["cancelled"] = r.cancelled;
  doc["stop_acknowledged"] = r.stop_acknowledged;
  doc["samples"] = r.samples;
  doc["dropped_samples"] = r.dropped_samples;
  const auto& s = r.link_stats;
  doc["link"] = {{"rx_bytes", s.rx_bytes},
                 {"tx_bytes", s.tx_bytes},
                 {"rx_messages", s.rx_messages},
                 {"tx_messages", s.tx_messages},
                 {"crc_errors", s.crc_errors},
                 {"sequence_errors", s.sequence_errors},
                 {"other_errors", s.other_errors},
                 {"link_losses", s.link_losses},
                 {"reconnect_attempts", s.reconnect_attempts},
                 {"rtt_mean_s", s.rtt_mean_s ? nlohmann::ordered_json(*s.rtt_mean_s)
                                             : nlohmann::ordered_json(nullptr)}};
  return doc.dump(2) + "\n";
}

}  // namespace irgs::app
