#include "app/sim/localization_run.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "core/io/atomic_file.hpp"
#include "core/sim/sim_presets.hpp"

namespace irgs::app {
namespace {

constexpr double kReachedRadius_m = 0.05;
constexpr double kStuckTime_s = 20.0;  // no progress for this long while driving: give up

// Turn on the spot towards the next waypoint, then drive straight with a heading correction.
VelocityCommand routeCommand(const Pose2& truth, const Vec2& goal, double speed_mps) {
  const Vec2 to_goal = goal - truth.position();
  const double heading_error = wrapAngle(std::atan2(to_goal.y(), to_goal.x()) - truth.theta);
  const double omega = std::clamp(2.0 * heading_error, -0.8, 0.8);
  const double v = std::abs(heading_error) > 0.15 ? 0.0 : std::min(speed_mps, to_goal.norm());
  return {v, omega};
}

double jsonNumber(double v) {
  return std::isfinite(v) ? v : -1.0;
}

}  // namespace

std::vector<Vec2> graphRoute(const WorldMap& map) {
  std::vector<Vec2> route;
  for (const TopoNode& node : map.graph.nodes)
    route.push_back(node.position);
  if (route.size() > 1)
    route.push_back(route.front());
  return route;
}

LocalizationRunResult runLocalization(const LocalizationRunSpec& spec) {
  SimConfig sim_config = spec.sim;
  if (!sim_config.gyro.enabled) {
    const std::uint64_t seed = sim_config.seed;
    sim_config.gyro = autogyroErrorModel();
    sim_config.seed = seed;
  }
  Simulator sim(spec.map, spec.profile, sim_config);
  sim.resetPose(spec.start);
  EstimatorRunnerConfig estimator = spec.estimator;
  estimator.kind = spec.kind;
  if (spec.kind == EstimatorKind::kEncoderGyro && !estimator.gyro_calibration)
    estimator.gyro_calibration = idealGyroCalibration(sim_config.gyro);
  EstimatorRunner runner(spec.map, spec.profile, spec.start, estimator);

  LocalizationRunResult result;
  TelemetrySample sample;
  std::size_t target = 0;
  double next_row_s = 0.0;
  std::int64_t last_readings = 0, last_accepted = 0;
  Vec2 progress_at = spec.start.position();
  double progress_time_s = 0.0;
  const auto max_steps = static_cast<std::int64_t>(std::ceil(spec.duration_s / sim_config.dt_s));
  auto addRow = [&](const EstimatorStep& step) {
    LocalizationSeriesRow row;
    row.time_s = step.time_s;
    row.truth = step.truth.value_or(Pose2{});
    row.estimate = step.estimate;
    row.dead_reckoning = step.dead_reckoning;
    row.covariance = step.covariance;
    row.nees = step.nees.value_or(-1.0);
    row.readings = static_cast<int>(runner.metrics().readings - last_readings);
    row.accepted = static_cast<int>(runner.metrics().accepted - last_accepted);
    last_readings = runner.metrics().readings;
    last_accepted = runner.metrics().accepted;
    result.series.push_back(row);
  };
  result.stopped_because = "duration";
  for (std::int64_t k = 0; k < max_steps; ++k) {
    const double t = sim.time_s();
    if (spec.script) {
      if (t > spec.script->lastTime_s()) {
        result.route_completed = true;
        result.stopped_because = "script done";
        break;
      }
      sim.setCommand(spec.script->commandAt(t));
    } else {
      while (target < spec.route.size() &&
             (spec.route[target] - sim.truePose().position()).norm() < kReachedRadius_m)
        ++target;
      if (target >= spec.route.size()) {
        result.route_completed = true;
        result.stopped_because = "route done";
        break;
      }
      sim.setCommand(routeCommand(sim.truePose(), spec.route[target], spec.speed_mps));
    }
    sim.step(sample);
    const EstimatorStep& step = runner.feed(sample);
    if (step.time_s + 1e-9 >= next_row_s) {
      addRow(step);
      next_row_s = step.time_s + spec.series_period_s;
    }
    // A route robot that neither advances nor turns is stuck against geometry.
    const Pose2& truth = sim.truePose();
    if ((truth.position() - progress_at).norm() > 0.05 ||
        std::abs(sim.trueVelocity().angular_radps) > 1e-3) {
      progress_at = truth.position();
      progress_time_s = t;
    } else if (!spec.script && t - progress_time_s > kStuckTime_s) {
      result.stopped_because = "robot stuck";
      break;
    }
  }
  if (result.series.empty() || result.series.back().time_s < runner.lastStep().time_s)
    addRow(runner.lastStep());
  result.metrics = runner.metrics();
  return result;
}

std::string localizationMetricsJson(const LocalizationRunSpec& spec, const LocalizationRunResult& r,
                                    const std::string& map_name, std::uint64_t seed) {
  const EstimatorMetrics& m = r.metrics;
  nlohmann::json j;
  j["estimator"] = toString(spec.kind);
  j["estimator_name"] = displayName(spec.kind);
  j["map"] = map_name;
  j["robot"] = spec.profile.name;
  j["seed"] = seed;
  j["route_completed"] = r.route_completed;
  j["stopped_because"] = r.stopped_because;
  j["duration_s"] = m.duration_s;
  j["distance_m"] = m.distance_m;
  j["estimate"] = {{"rms_position_error_m", m.rms_position_error_m},
                   {"rms_heading_error_deg", radToDeg(m.rms_heading_error_rad)},
                   {"max_position_error_m", m.max_position_error_m},
                   {"final_position_error_m", m.final_position_error_m},
                   {"final_heading_error_deg", radToDeg(m.final_heading_error_rad)}};
  j["dead_reckoning"] = {{"rms_position_error_m", m.dr_rms_position_error_m},
                         {"final_position_error_m", m.dr_final_position_error_m},
                         {"final_heading_error_deg", radToDeg(m.dr_final_heading_error_rad)}};
  j["nees"] = {{"steps", m.nees_steps},
               {"mean", jsonNumber(m.mean_nees)},
               {"fraction_within_95", m.nees_within_95},
               {"bound_95_3dof", kChi2Dof3P95}};
  j["measurements"] = {{"kind", spec.kind == EstimatorKind::kEncoderGyro     ? "gyro heading"
                                : usesStereo(spec.kind)                      ? "stereo echoes"
                                : spec.kind == EstimatorKind::kMouseOdometry ? "floor-sensor counts"
                                                                             : "none"},
                       {"received", m.readings},
                       {"accepted", m.accepted},
                       {"accepted_fraction", m.acceptedFraction()}};
  if (spec.kind == EstimatorKind::kStereoEkfCaster)
    j["caster"] = {{"lambda", spec.estimator.caster_lambda},
                   {"period_s", spec.estimator.caster_period_s},
                   {"periods", m.caster_periods},
                   {"mean_residual_rad", m.mean_caster_residual_rad}};
  j["units"] = "metres, degrees (headings), seconds";
  return j.dump(2) + "\n";
}

std::string localizationSeriesCsv(const LocalizationRunResult& r) {
  std::string out =
      "time_s,true_x_m,true_y_m,true_theta_deg,est_x_m,est_y_m,est_theta_deg,dr_x_m,dr_y_m,"
      "dr_theta_deg,err_x_m,err_y_m,err_pos_m,err_theta_deg,dr_err_pos_m,sigma_x_m,sigma_y_m,"
      "sigma_theta_deg,cov_xy_m2,nees,readings,accepted\n";
  char line[512];
  for (const LocalizationSeriesRow& row : r.series) {
    const double ex = row.estimate.x - row.truth.x, ey = row.estimate.y - row.truth.y;
    const double et = wrapAngle(row.estimate.theta - row.truth.theta);
    const double dr =
        std::hypot(row.dead_reckoning.x - row.truth.x, row.dead_reckoning.y - row.truth.y);
    const LocCov& p = row.covariance;
    std::snprintf(line, sizeof line,
                  "%.3f,%.4f,%.4f,%.3f,%.4f,%.4f,%.3f,%.4f,%.4f,%.3f,%.4f,%.4f,%.4f,%.4f,%.4f,"
                  "%.5f,%.5f,%.4f,%.6g,%.4g,%d,%d\n",
                  row.time_s, row.truth.x, row.truth.y, radToDeg(row.truth.theta), row.estimate.x,
                  row.estimate.y, radToDeg(row.estimate.theta), row.dead_reckoning.x,
                  row.dead_reckoning.y, radToDeg(row.dead_reckoning.theta), ex, ey,
                  std::hypot(ex, ey), radToDeg(et), dr, std::sqrt(std::max(0.0, p(0, 0))),
                  std::sqrt(std::max(0.0, p(1, 1))), radToDeg(std::sqrt(std::max(0.0, p(2, 2)))),
                  p(0, 1), row.nees, row.readings, row.accepted);
    out += line;
  }
  return out;
}

LocalizationRunOutcome runLocalizationMode(const SimOptions& options, const WorldMap& map,
                                           const RobotProfile& profile) {
  LocalizationRunOutcome outcome;
  LocalizationRunSpec spec;
  spec.map = map;
  spec.profile = profile;
  spec.start = options.start.value_or(map.start);
  spec.kind = parseEstimatorKind(options.localize).value_or(EstimatorKind::kStereoEkf);
  spec.sim = options.ideal ? idealSimConfig(spec.sim) : typicalSimConfig(spec.sim);
  spec.sim.seed = options.seed;
  spec.estimator.seed = options.seed;
  if (options.caster_lambda)
    spec.estimator.caster_lambda = *options.caster_lambda;
  // The three-caster EKF predicts every dead-reckoning period of 000 (1 ms) from that period's
  // encoder increments: step the simulator at that period so it sees each one (a coarser step
  // averages the wheels' random slip and hides it from the adaptive noise lambda ||e||).
  if (spec.kind == EstimatorKind::kStereoEkfCaster)
    spec.sim.dt_s = spec.estimator.caster_period_s;
  if (options.duration_s)
    spec.duration_s = *options.duration_s;
  if (!options.script.empty()) {
    auto script = loadDriveScriptFile(options.script);
    if (!script.script) {
      outcome.exit_code = 1;
      outcome.error = "cannot load drive script " + options.script.string();
      for (const auto& d : script.diagnostics)
        outcome.error += "\n" + d.toString();
      return outcome;
    }
    spec.script = std::move(*script.script);
  } else {
    spec.route = options.route.empty() ? graphRoute(map) : options.route;
    if (spec.route.empty()) {
      outcome.exit_code = 3;
      outcome.error =
          "--localize needs a route: --route X,Y;..., a map with a route graph (\"graph\" "
          "nodes) or --script FILE";
      return outcome;
    }
  }
  LocalizationRunResult result;
  try {
    result = runLocalization(spec);
  } catch (const std::invalid_argument& e) {
    outcome.exit_code = 3;
    outcome.error = e.what();
    return outcome;
  }

  std::error_code ec;
  std::filesystem::create_directories(options.out, ec);
  const std::string map_name = options.map.filename().string();
  const std::vector<std::pair<std::string, std::string>> files = {
      {"localization_metrics.json", localizationMetricsJson(spec, result, map_name, options.seed)},
      {"localization.csv", localizationSeriesCsv(result)}};
  for (const auto& [name, text] : files) {
    const std::filesystem::path path = options.out / name;
    if (const auto error = writeFileAtomically(path, text)) {
      outcome.exit_code = 1;
      outcome.error = *error;
      return outcome;
    }
    outcome.written.push_back(path);
  }
  const EstimatorMetrics& m = result.metrics;
  char line[512];
  std::snprintf(line, sizeof line,
                "--localize %s: %.1f s, %.1f m (%s); estimate RMS %.3f m, max %.3f m, final "
                "%.3f m / %.2f deg; dead reckoning final %.3f m; NEES within 95 %% bound %.1f %% "
                "of steps; %lld/%lld measurements accepted",
                toString(spec.kind), m.duration_s, m.distance_m, result.stopped_because.c_str(),
                m.rms_position_error_m, m.max_position_error_m, m.final_position_error_m,
                radToDeg(m.final_heading_error_rad), m.dr_final_position_error_m,
                100.0 * m.nees_within_95, static_cast<long long>(m.accepted),
                static_cast<long long>(m.readings));
  outcome.summary = line;
  if (!result.route_completed && result.stopped_because == "robot stuck") {
    outcome.exit_code = 3;
    outcome.error = "the robot got stuck before the end of the route (outputs written)";
  }
  return outcome;
}

}  // namespace irgs::app
