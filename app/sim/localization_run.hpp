#pragma once
// irgs-sim --localize ekf|dr|encoder-gyro|mouse|ekf-caster: one localization experiment, headless.
// The simulated robot drives a route (the map's route graph, node by node and back to the first; or
// a timed drive script) while an EstimatorRunner (core/estimation/estimator_runner.hpp) estimates
// its pose; writes the metrics (RMS and final errors, NEES, accepted fraction) as JSON and the time
// series as CSV. The route is driven on the TRUE pose, so every estimator sees the same motion
// and a diverging one cannot steer the robot into a wall.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "app/sim/sim_options.hpp"
#include "core/estimation/estimator_runner.hpp"
#include "core/robot/robot_profile.hpp"
#include "core/sim/drive_script.hpp"
#include "core/sim/simulator.hpp"
#include "core/world/world_map.hpp"

namespace irgs::app {

struct LocalizationRunSpec {
  WorldMap map;
  RobotProfile profile;
  Pose2 start;
  EstimatorKind kind = EstimatorKind::kStereoEkf;
  std::vector<Vec2> route;  // waypoints after the start; ignored when script is set
  std::optional<DriveScript> script;
  double speed_mps = 0.3;        // route cruise speed [000: 0.3 m/s]
  double duration_s = 3600.0;    // budget (the route ends the run earlier)
  double series_period_s = 0.1;  // one CSV row per period (and the last sample)
  SimConfig sim;  // the gyro is switched on (AUTOGYRO level) unless already configured
  EstimatorRunnerConfig estimator;
};

struct LocalizationSeriesRow {
  double time_s = 0.0;
  Pose2 truth, estimate, dead_reckoning;
  LocCov covariance = LocCov::Zero();
  double nees = -1.0;  // -1: undefined (P not positive definite)
  int readings = 0;    // echoes (or gyro samples) since the previous row
  int accepted = 0;
};

struct LocalizationRunResult {
  EstimatorMetrics metrics;
  bool route_completed = false;  // every waypoint reached (route mode), script played out
  std::vector<LocalizationSeriesRow> series;
  std::string stopped_because;  // "route done", "duration", "robot stuck"
};

// Throws std::invalid_argument for what Simulator/EstimatorRunner refuse (bad profile, config).
LocalizationRunResult runLocalization(const LocalizationRunSpec& spec);

// The route of a map's graph: its nodes in file order, then back to the first. Empty without a
// graph.
std::vector<Vec2> graphRoute(const WorldMap& map);

std::string localizationMetricsJson(const LocalizationRunSpec& spec,
                                    const LocalizationRunResult& result,
                                    const std::string& map_name, std::uint64_t seed);
std::string localizationSeriesCsv(const LocalizationRunResult& result);

struct LocalizationRunOutcome {
  int exit_code = 0;  // 0 success, 1 a file could not be written, 3 no route to drive
  std::string summary;
  std::vector<std::filesystem::path> written;
  std::string error;
};

// From the command line: writes localization_metrics.json and localization.csv into options.out.
LocalizationRunOutcome runLocalizationMode(const SimOptions& options, const WorldMap& map,
                                           const RobotProfile& profile);

}  // namespace irgs::app
