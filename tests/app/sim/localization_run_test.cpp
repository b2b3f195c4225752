// irgs-sim --localize: the experiment behind it (app/sim/localization_run.hpp), its outputs and
// its command line.

#include "app/sim/localization_run.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "core/robot/robot_profile_file.hpp"
#include "core/sim/sim_presets.hpp"
#include "core/world/map_file.hpp"

namespace irgs::app {
namespace {

LocalizationRunSpec corridorSpec(EstimatorKind kind, std::uint64_t seed) {
  LocalizationRunSpec spec;
  const auto map =
      loadMapFile(std::string(IRGS_SOURCE_DIR) + "/resources/maps/corridor_000_table1.json");
  const auto robot =
      loadRobotProfileFile(std::string(IRGS_SOURCE_DIR) + "/resources/robots/thesis_robot.json");
  EXPECT_TRUE(map.map && robot.profile);
  spec.map = *map.map;
  spec.profile = *robot.profile;
  spec.start = spec.map.start;
  spec.route = graphRoute(spec.map);
  spec.kind = kind;
  spec.sim = typicalSimConfig();
  spec.sim.seed = seed;
  spec.estimator.seed = seed;
  return spec;
}

TEST(LocalizationRun, TheGraphRouteVisitsEveryNodeAndClosesTheLoop) {
  const LocalizationRunSpec spec = corridorSpec(EstimatorKind::kStereoEkf, 1);
  ASSERT_EQ(spec.route.size(), spec.map.graph.nodes.size() + 1);
  EXPECT_EQ(spec.route.front(), spec.route.back());
  EXPECT_TRUE(graphRoute(WorldMap{}).empty());
}

// The lap of the 000 corridor runs hugging the central block: the walls stay within the 2.06 m
// reach of the 12 ms TOF gate.
const std::vector<Vec2> kHuggingLap = {
    {15.9, 0.775}, {15.9, -14.55}, {-1.0, -14.55}, {-1.0, 0.775}, {2.0, 0.775}};

TEST(LocalizationRun, OnTheCorridorTheEkfErrorIsBoundedWhileDeadReckoningGrows) {
  for (std::uint64_t seed : {1u, 2u}) {
    LocalizationRunSpec spec = corridorSpec(EstimatorKind::kStereoEkf, seed);
    spec.route = kHuggingLap;
    const LocalizationRunResult r = runLocalization(spec);
    const EstimatorMetrics& m = r.metrics;
    EXPECT_TRUE(r.route_completed) << r.stopped_because;
    EXPECT_GT(m.distance_m, 60.0);
    EXPECT_LT(m.max_position_error_m, 0.15) << "seed " << seed;
    EXPECT_LT(m.rms_position_error_m, 0.05) << "seed " << seed;
    EXPECT_GT(m.dr_final_position_error_m, 5.0 * m.final_position_error_m) << "seed " << seed;
    EXPECT_GT(m.dr_rms_position_error_m, 3.0 * m.rms_position_error_m) << "seed " << seed;
    EXPECT_GE(m.nees_within_95, 0.9) << "seed " << seed;
    EXPECT_GT(m.acceptedFraction(), 0.5) << "seed " << seed;
    ASSERT_GT(r.series.size(), 100u);
    // DR error grows: the end is worse than the first quarter.
    const auto& s = r.series;
    auto dr = [](const LocalizationSeriesRow& row) {
      return (row.dead_reckoning.position() - row.truth.position()).norm();
    };
    EXPECT_GT(dr(s.back()), dr(s[s.size() / 4]));
  }
}

TEST(LocalizationRun, OnTheMidCorridorGraphRouteTheEkfCoastsWhereNoWallIsInRange) {
  // The map's graph runs 3.8-4.75 m from the walls in the wide east and west legs: no echo
  // there, the EKF predicts only and its error grows like dead reckoning's until a wall comes
  // back into range. Still far better than dead reckoning over the loop.
  const LocalizationRunResult r = runLocalization(corridorSpec(EstimatorKind::kStereoEkf, 1));
  EXPECT_TRUE(r.route_completed) << r.stopped_because;
  EXPECT_GT(r.metrics.distance_m, 75.0);
  EXPECT_LT(r.metrics.rms_position_error_m, 0.5 * r.metrics.dr_rms_position_error_m);
  EXPECT_LT(r.metrics.final_position_error_m, 0.5 * r.metrics.dr_final_position_error_m);
  // Stretches without readings exist: rows with no echo for 10 s running.
  int longest = 0, run = 0;
  for (const LocalizationSeriesRow& row : r.series) {
    run = row.readings == 0 ? run + 1 : 0;
    longest = std::max(longest, run);
  }
  EXPECT_GT(longest, 100);
}

TEST(LocalizationRun, DeadReckoningAloneHasAGrowingCovarianceAndNoMeasurements) {
  LocalizationRunSpec spec = corridorSpec(EstimatorKind::kDeadReckoning, 3);
  spec.duration_s = 60.0;
  const LocalizationRunResult r = runLocalization(spec);
  EXPECT_EQ(r.stopped_because, "duration");
  EXPECT_EQ(r.metrics.readings, 0);
  EXPECT_GT(r.series.back().covariance(0, 0), 4.0 * r.series.front().covariance(0, 0));
  // Dead reckoning is its own estimate (the EKF prediction and the arc integration agree).
  EXPECT_NEAR(r.metrics.final_position_error_m, r.metrics.dr_final_position_error_m, 1e-6);
}

TEST(LocalizationRun, MetricsJsonAndSeriesCsvCarryTheNumbers) {
  LocalizationRunSpec spec = corridorSpec(EstimatorKind::kStereoEkf, 4);
  spec.duration_s = 20.0;
  const LocalizationRunResult r = runLocalization(spec);
  const auto j = nlohmann::json::parse(localizationMetricsJson(spec, r, "corridor.json", 4));
  EXPECT_EQ(j["estimator"], "ekf");
  EXPECT_EQ(j["seed"], 4);
  EXPECT_NEAR(j["estimate"]["rms_position_error_m"].get<double>(), r.metrics.rms_position_error_m,
              1e-12);
  EXPECT_TRUE(j["nees"].contains("fraction_within_95"));
  EXPECT_TRUE(j["measurements"].contains("accepted_fraction"));
  const std::string csv = localizationSeriesCsv(r);
  std::istringstream in(csv);
  std::string header, line;
  std::getline(in, header);
  EXPECT_EQ(header.rfind("time_s,true_x_m,true_y_m,true_theta_deg,est_x_m", 0), 0u);
  const auto columns = std::count(header.begin(), header.end(), ',');
  std::size_t rows = 0;
  while (std::getline(in, line)) {
    EXPECT_EQ(std::count(line.begin(), line.end(), ','), columns);
    ++rows;
  }
  EXPECT_EQ(rows, r.series.size());
  EXPECT_NEAR(static_cast<double>(rows), 20.0 / spec.series_period_s, 3.0);
}

TEST(LocalizationRun, TheCommandLineTakesTheEstimatorAndRefusesNonsense) {
  auto parse = [](std::vector<std::string> args) { return parseSimOptions(args); };
  const auto ok = parse({"--map", "m.json", "--out", "o", "--localize", "encoder-gyro"});
  ASSERT_TRUE(ok.options) << ok.error;
  EXPECT_EQ(ok.options->localize, "encoder-gyro");
  const auto bad = parse({"--map", "m.json", "--out", "o", "--localize", "kalman"});
  EXPECT_FALSE(bad.options);
  EXPECT_NE(bad.error.find("ekf, dr, encoder-gyro, mouse or ekf-caster"), std::string::npos);
  const auto caster = parse(
      {"--map", "m.json", "--out", "o", "--localize", "ekf-caster", "--caster-lambda", "0.05"});
  ASSERT_TRUE(caster.options) << caster.error;
  EXPECT_EQ(caster.options->caster_lambda, 0.05);
  // lambda belongs to the caster EKF and is a non-negative scale.
  EXPECT_FALSE(
      parse({"--map", "m.json", "--out", "o", "--localize", "ekf", "--caster-lambda", "0.05"})
          .options);
  EXPECT_FALSE(
      parse({"--map", "m.json", "--out", "o", "--localize", "ekf-caster", "--caster-lambda", "-1"})
          .options);
  EXPECT_FALSE(
      parse({"--map", "m.json", "--out", "o", "--localize", "ekf", "--behaviour", "coverage"})
          .options);
  EXPECT_NE(simUsage().find("--localize"), std::string::npos);
  const auto route = parse(
      {"--map", "m.json", "--out", "o", "--localize", "ekf", "--route", "15.9,0.775;15.9,-14.55"});
  ASSERT_TRUE(route.options) << route.error;
  ASSERT_EQ(route.options->route.size(), 2u);
  EXPECT_DOUBLE_EQ(route.options->route[1].y(), -14.55);
  EXPECT_FALSE(
      parse({"--map", "m.json", "--out", "o", "--localize", "ekf", "--route", "1,x"}).options);
  EXPECT_FALSE(parse({"--map", "m.json", "--out", "o", "--route", "1,2"}).options);
}

TEST(LocalizationRun, AMapWithoutARouteIsAnExpectedFailure) {
  SimOptions options;
  options.localize = "ekf";
  options.out = "/nonexistent/never-written";
  WorldMap map;
  const auto robot =
      loadRobotProfileFile(std::string(IRGS_SOURCE_DIR) + "/resources/robots/thesis_robot.json");
  const LocalizationRunOutcome outcome = runLocalizationMode(options, map, *robot.profile);
  EXPECT_EQ(outcome.exit_code, 3);
  EXPECT_NE(outcome.error.find("route"), std::string::npos);
  EXPECT_TRUE(outcome.written.empty());
}

}  // namespace
}  // namespace irgs::app
