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

#include "comms/robot/linked_robot.hpp"
#include "comms/transport/io_thread.hpp"
#include "core/mapping/sonar_mapper.hpp"

namespace irgs::app {

namespace {

using Clock = std::chrono::steady_clock;
constexpr auto kLoopPeriod = std::chrono::milliseconds(16);  // drain like the GUI (60 Hz)

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

  const auto url = comms::parseLinkUrl(spec.url);
  if (!url.url) {
    out.error = "bad --connect URL '" + spec.url + "': " + url.error;
    return out;
  }
  comms::IoThread io;
  auto opened = comms::LinkedRobot::open(io, *url.url, spec.profile);
  if (!opened.robot) {
    out.error = "cannot open " + spec.url + ": " + opened.error;
    return out;
  }
  comms::LinkedRobot& robot = *opened.robot;
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
    for (auto& s : robot.update(0.0))
      pending.push_back(std::move(s));
    if (robot.linkState() == comms::LinkState::kConnected && !pending.empty())
      break;
    if (secondsSince(connect_start) > spec.connect_timeout_s) {
      out.error = robot.linkState() == comms::LinkState::kConnected
                      ? "the robot at " + spec.url + " is connected but sent no odometry within " +
                            seconds(spec.connect_timeout_s) + " s"
                      : "no robot heartbeat from " + spec.url + " within " +
                            seconds(spec.connect_timeout_s) + " s" +
                            (last_event.empty() ? "" : " (last: " + last_event + ")");
      out.link_stats = robot.linkStats();
      return out;
    }
    std::this_thread::sleep_for(kLoopPeriod);
  }
  if (cancelled() && pending.empty()) {
    out.error = "interrupted before the robot was connected";
    out.cancelled = true;
    return out;
  }
  log("connected to " + robot.describe() + ": running the script for " + seconds(spec.duration_s) +
      " s");

  // 2. Drive the script on the wall clock and integrate every sample.
  ScenarioResult result{OccupancyGrid(spec.grid_resolution_m), {}, {}};
  ScenarioMetrics& m = result.metrics;
  std::optional<double> first_time_s;
  std::optional<double> next_row_s;
  std::optional<Pose2> previous_pose;
  std::uint32_t previous_bumpers = 0;
  VelocityCommand command;
  TrajectoryRow last_row;
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
  };
  for (const auto& s : pending)
    integrate(s);
  pending.clear();

  const Clock::time_point run_start = Clock::now();
  bool was_connected = true;
  while (!cancelled()) {
    const double elapsed = secondsSince(run_start);
    if (elapsed >= spec.duration_s)
      break;
    command = spec.script.commandAt(elapsed);
    robot.drive(command);  // sent when it changes; LinkedRobot repeats it while non-zero
    for (const auto& s : robot.update(0.0))
      integrate(s);
    drainEvents();
    const bool connected = robot.linkState() == comms::LinkState::kConnected;
    if (connected && !was_connected)
      log("link back: the script continues at " + seconds(elapsed) + " s");
    was_connected = connected;
    std::this_thread::sleep_for(kLoopPeriod);
  }
  out.cancelled = cancelled();

  // 3. Stop the robot and wait (bounded) for the acknowledgement and the last samples.
  command = {};
  std::atomic<bool> acked{false};
  std::atomic<bool> answered{false};
  robot.drive({});
  robot.sendBehaviour({.kind = comms::RobotBehaviourKind::kStop},
                      [&acked, &answered](const comms::CommandResult& r) {
                        acked = r.outcome == comms::CommandOutcome::kAccepted;
                        answered = true;
                      });
  const Clock::time_point stop_start = Clock::now();
  while (!answered && secondsSince(stop_start) < spec.stop_timeout_s) {
    for (const auto& s : robot.update(0.0))
      integrate(s);
    drainEvents();
    std::this_thread::sleep_for(kLoopPeriod);
  }
  out.stop_acknowledged = acked;
  if (!out.stop_acknowledged)
    log("warning: the robot did not acknowledge the final stop (its teleop timeout stops it)");
  for (const auto& s : robot.update(0.0))
    integrate(s);
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
  out.dropped_samples = robot.droppedSamples();
  out.link_stats = robot.linkStats();
  out.result = std::move(result);
  return out;
}

std::string linkedRunJson(const LinkedRunSpec& spec, const LinkedRunResult& r) {
  nlohmann::ordered_json doc;
  doc["url"] = spec.url;
  doc["truth"] =
      "not available from a linked robot: trajectory.csv true_* columns and final_true_pose "
      "repeat the odometry, odometry_error is not measured (null), grid.png shows one path";
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
