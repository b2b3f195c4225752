#include "app/sim/behaviour_run.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string_view>

#include "app/sim/map_compare.hpp"
#include "core/io/atomic_file.hpp"
#include "core/mapping/map_score.hpp"
#include "core/mission/travel_mission.hpp"
#include "core/planning/astar.hpp"
#include "core/planning/coverage.hpp"
#include "core/planning/path_amendment.hpp"
#include "core/planning/planning_grid.hpp"
#include "core/planning/traveling.hpp"
#include "core/scenario/behaviour_runner.hpp"
#include "core/scenario/scenario_outputs.hpp"
#include "core/sim/sim_presets.hpp"

namespace irgs::app {
namespace {

constexpr int kExitFiles = 1;
constexpr int kExitBehaviourFailed = 3;
constexpr double kPlanResolution_m = 0.05;

double rounded(double v, int digits = 4) {
  const double f = std::pow(10.0, digits);
  return std::round(v * f) / f;
}

std::string pointsCsv(const std::vector<Vec2>& points, const char* header) {
  std::ostringstream out;
  out << header << "\n";
  char line[96];
  for (const Vec2& p : points) {
    std::snprintf(line, sizeof line, "%.4f,%.4f\n", p.x(), p.y());
    out << line;
  }
  return out.str();
}

// The planning grid of the true map (the host plans on the known map), inflated by the body
// radius plus a 5 cm margin.
PlanningGrid plannerGrid(const WorldMap& map, const RobotProfile& profile) {
  PlanningGridOptions opt;
  opt.robot_radius_m = profile.bodyRadius() + 0.05;
  if (map.raster && map.walls.empty() && map.obstacles.empty())
    return planningGridFromRaster(map.raster->raster, opt);
  return planningGridFromWorld(map, kPlanResolution_m, opt, 0.2);
}

// Fraction of the free cells reachable from the start (on `grid`) that the true path passed
// within half a lane of.
double executedCoverage(const PlanningGrid& grid, const Pose2& start,
                        const std::vector<TrajectoryRow>& rows, double half_lane_m) {
  const auto s = grid.worldToCell(start.position());
  if (!s || !grid.isFree(*s))
    return 0.0;
  std::vector<std::uint8_t> reach(grid.cellCount(), 0), seen(grid.cellCount(), 0);
  std::vector<std::size_t> stack{grid.index(*s)};
  reach[stack.back()] = 1;
  while (!stack.empty()) {
    const Cell c = grid.cellOf(stack.back());
    stack.pop_back();
    for (int dr = -1; dr <= 1; ++dr)
      for (int dc = -1; dc <= 1; ++dc) {
        const Cell n{c.col + dc, c.row + dr};
        if (!grid.isFree(n) || reach[grid.index(n)])
          continue;
        reach[grid.index(n)] = 1;
        stack.push_back(grid.index(n));
      }
  }
  const int r = static_cast<int>(std::ceil(half_lane_m / grid.resolution_m));
  for (const TrajectoryRow& row : rows) {
    const auto c = grid.worldToCell(row.truth.position());
    if (!c)
      continue;
    for (int dr = -r; dr <= r; ++dr)
      for (int dc = -r; dc <= r; ++dc) {
        const Cell n{c->col + dc, c->row + dr};
        if (grid.inside(n) && std::hypot(dc, dr) * grid.resolution_m <= half_lane_m)
          seen[grid.index(n)] = 1;
      }
  }
  std::size_t total = 0, covered = 0;
  for (std::size_t i = 0; i < reach.size(); ++i) {
    total += reach[i];
    covered += reach[i] & seen[i];
  }
  return total ? static_cast<double>(covered) / static_cast<double>(total) : 0.0;
}

}  // namespace

std::optional<std::string> prepareBehaviourJob(const SimOptions& options, const WorldMap* map,
                                               const RobotProfile& profile, const Pose2& start,
                                               BehaviourJob& job) {
  job = BehaviourJob{};
  job.kind = options.behaviour;
  job.start = start;
  try {
    if (options.behaviour == "mapbuild") {
      MapBuildingConfig config;
      config.grid_resolution_m = options.grid_resolution_m;
      config.max_time_s = options.duration_s.value_or(3600.0);
      auto b = std::make_unique<MapBuildingMission>(profile, config);
      job.builder = b.get();
      job.mission = std::move(b);
      return std::nullopt;
    }
    if (options.behaviour != "goal" && options.behaviour != "coverage")
      return "unknown behaviour '" + options.behaviour + "'";
    if (map == nullptr)
      return "--behaviour " + options.behaviour + " plans on the map: give --map";
    job.plan_grid = plannerGrid(*map, profile);
    const PlanningGrid& plan_grid = job.plan_grid;
    const auto s = plan_grid.worldToCell(start.position());
    if (!s || !plan_grid.isFree(*s))
      return "the start pose is outside the map or too close to an obstacle to plan";
    TravelPlan travel;
    if (options.behaviour == "goal") {
      const auto g = options.goal ? plan_grid.worldToCell(*options.goal) : std::nullopt;
      if (!g || !plan_grid.isFree(*g))
        return "the goal is outside the map or too close to an obstacle";
      const PlanResult raw = planAStar(plan_grid, *s, *g);
      if (!raw.found())
        return "no path to the goal (" + std::string(toString(raw.status)) + ")";
      const AmendResult amended = amendPath(plan_grid, raw.points, {});
      job.planned = amended.points;
      job.planned.front() = start.position();
      job.planned.back() = *options.goal;
      travel = makeTravelPlan(job.planned, start.theta, degToRad(15.0));
      job.extra["goal"] = {{"x", options.goal->x()}, {"y", options.goal->y()}};
      job.extra["plan"] = {{"astar_length_m", rounded(amended.length_before_m)},
                           {"astar_turns", amended.turns_before},
                           {"amended_length_m", rounded(amended.length_after_m)},
                           {"amended_turns", amended.turns_after},
                           {"amended_time_s", rounded(amended.time_after_s)},
                           {"astar_time_s", rounded(amended.time_before_s)},
                           {"segments", travel.segments.size()}};
    } else {
      CoverageOptions copt;
      double lane_m = 2.0 * (profile.bodyRadius() - 0.02);  // overlap the lanes slightly
      copt.lane_cells = std::max(1, static_cast<int>(lane_m / plan_grid.resolution_m));
      lane_m = copt.lane_cells * plan_grid.resolution_m;
      job.lane_m = lane_m;
      const CoveragePlan cov = planCoverage(plan_grid, *s, copt);
      if (!cov.ok || cov.points.size() < 2)
        return "no coverage path from the start";
      job.planned = cov.points;
      job.planned.insert(job.planned.begin(), start.position());
      travel = makeTravelPlan(job.planned, start.theta, degToRad(15.0));
      job.extra["plan"] = {{"pattern", "spiral"},
                           {"lane_m", rounded(lane_m)},
                           {"planned_coverage", rounded(cov.coverage)},
                           {"length_m", rounded(cov.length_m)},
                           {"turns", cov.turns},
                           {"segments", travel.segments.size()}};
    }
    job.mission = std::make_unique<TravelMission>(job.planned);
  } catch (const std::exception& e) {
    return std::string("cannot set up the behaviour: ") + e.what();
  }
  return std::nullopt;
}

BehaviourRunOutcome writeBehaviourOutputs(const SimOptions& options, BehaviourJob& job,
                                          BehaviourScenarioResult& result,
                                          BehaviourOutputInfo info) {
  BehaviourRunOutcome outcome;
  nlohmann::json extra = job.extra;
  for (const auto& [key, value] : info.extra.items())
    extra[key] = value;
  const auto scoreJson = [](const MapScore& score) {
    return nlohmann::json{{"precision", rounded(score.precision)},
                          {"recall", rounded(score.recall)},
                          {"f1", rounded(score.f1)},
                          {"resolution_m", score.resolution_m},
                          {"tolerance_cells", MapScoreOptions{}.tolerance_cells},
                          {"built_cells", score.built_cells},
                          {"truth_cells", score.truth_cells}};
  };
  if (MapBuildingMission* builder = job.builder) {
    result.scenario.grid = builder->grid();  // the map the behaviour built (revised poses)
    if (info.truth) {
      try {
        extra["map_score"] = scoreJson(scoreMap(builder->grid(), *info.truth, job.start));
      } catch (const std::exception& e) {
        // No ground truth to score against (e.g. a start inside a wall): say so, keep the run.
        extra["map_score"] = {{"error", e.what()}};
      }
    }
    if (!options.compare.empty()) {
      const MapAgreement agreement = compareWithSavedMap(builder->grid(), options.compare);
      if (agreement.score) {
        extra["map_agreement"] = scoreJson(*agreement.score);
        extra["map_agreement"]["reference"] = options.compare.string();
      } else {
        extra["map_agreement"] = {{"error", agreement.error}};
      }
    }
    extra["map_building"] = {
        {"indices", builder->allIndices().size()},
        {"obstacles", builder->obstacleCount()},
        {"first_wall_was_obstacle", builder->firstWallWasObstacle()},
        {"outline_area_m2",
         builder->outline() ? rounded(-builder->outline()->signed_area_m2) : 0.0},
        {"heading_corrections", builder->revisedPose().headingCorrections()},
        {"interior_targets", builder->interiorTargetsVisited()}};
    job.planned = builder->allIndices();
  } else if (job.kind == "goal") {
    const Vec2 end = result.scenario.metrics.final_truth.position();
    extra["goal_error_m"] = rounded((end - *options.goal).norm());
  } else {
    extra["coverage"] =
        job.lane_m > 0.0 ? rounded(executedCoverage(job.plan_grid, job.start,
                                                    result.scenario.trajectory, 0.5 * job.lane_m))
                         : 0.0;
  }

  const WriteOutputsResult written = writeScenarioOutputs(result.scenario, info.run, options.out);
  outcome.written = written.written;
  if (!written.error.empty()) {
    outcome.exit_code = kExitFiles;
    outcome.error = written.error;
    return outcome;
  }
  const auto write = [&](const std::string& name, const std::string& text) {
    const auto path = options.out / name;
    if (const auto err = writeFileAtomically(path, text)) {
      outcome.exit_code = kExitFiles;
      outcome.error = *err;
      return false;
    }
    // metrics.json replaces the scenario's: list it once.
    if (std::find(outcome.written.begin(), outcome.written.end(), path) == outcome.written.end())
      outcome.written.push_back(path);
    return true;
  };
  if (!write("metrics.json", behaviourMetricsJson(result, info.run, extra)))
    return outcome;
  const bool builder = job.builder != nullptr;
  if (!write(builder ? "indices.csv" : "plan.csv",
             pointsCsv(job.planned, builder ? "index_x_m,index_y_m" : "x_m,y_m")))
    return outcome;
  for (const auto& [name, text] : info.extra_files)
    if (!write(name, text))
      return outcome;

  const BehaviourMetrics& b = result.behaviour;
  std::string scores;
  char number[64];
  for (const char* key : {"map_score", "map_agreement"})
    if (extra.contains(key) && extra[key].contains("f1")) {
      std::snprintf(number, sizeof number, ", F1 %.4f%s", extra[key]["f1"].get<double>(),
                    std::string_view(key) == "map_score" ? "" : " against the reference");
      scores += number;
    }
  char line[512];
  std::snprintf(line, sizeof line, "%s %s after %.1f s %s (%.2f s wall), %.2f m, %d turns%s",
                b.behaviour.c_str(), b.failed ? "FAILED" : "finished",
                result.scenario.metrics.duration_s, info.clock, b.wall_clock_s,
                result.scenario.metrics.distance_travelled_m, b.turns, scores.c_str());
  outcome.summary = std::string(line) + ": " + b.message;
  if (b.failed)
    outcome.exit_code = kExitBehaviourFailed;
  return outcome;
}

BehaviourRunOutcome runBehaviourMode(const SimOptions& options, const WorldMap& map,
                                     const RobotProfile& profile,
                                     const std::function<double()>& clock) {
  BehaviourRunOutcome outcome;
  const Pose2 start = options.start.value_or(map.start);
  BehaviourJob job;
  if (const auto error = prepareBehaviourJob(options, &map, profile, start, job)) {
    outcome.exit_code = kExitBehaviourFailed;
    outcome.error = *error;
    return outcome;
  }
  BehaviourScenarioSpec spec;
  spec.map = map;
  spec.profile = profile;
  spec.start = start;
  spec.sim = options.ideal ? idealSimConfig() : typicalSimConfig();
  spec.sim.seed = options.seed;
  spec.max_duration_s = options.duration_s.value_or(3600.0);
  spec.grid_resolution_m = options.grid_resolution_m;
  spec.wall_clock = clock;
  BehaviourScenarioResult result = runMissionScenario(spec, *job.mission);
  BehaviourOutputInfo info;
  info.run = {options.map.filename().string(), profile.name, options.seed};
  info.truth = &map;
  return writeBehaviourOutputs(options, job, result, std::move(info));
}

}  // namespace irgs::app
