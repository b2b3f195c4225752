#include "app/sim/behaviour_run.hpp"

#include <cmath>
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/behaviour/map_building.hpp"
#include "core/behaviour/travel_behaviour.hpp"
#include "core/io/atomic_file.hpp"
#include "core/mapping/map_score.hpp"
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

BehaviourRunOutcome runBehaviourMode(const SimOptions& options, const WorldMap& map,
                                     const RobotProfile& profile,
                                     const std::function<double()>& clock) {
  BehaviourRunOutcome outcome;
  BehaviourScenarioSpec spec;
  spec.map = map;
  spec.profile = profile;
  spec.start = options.start;
  spec.sim = options.ideal ? idealSimConfig() : typicalSimConfig();
  spec.sim.seed = options.seed;
  spec.max_duration_s = options.duration_s.value_or(3600.0);
  spec.grid_resolution_m = options.grid_resolution_m;
  spec.wall_clock = clock;
  const Pose2 start = options.start.value_or(map.start);

  nlohmann::json extra = nlohmann::json::object();
  std::unique_ptr<Behaviour> behaviour;
  MapBuildingBehaviour* builder = nullptr;
  std::vector<Vec2> planned;
  PlanningGrid plan_grid;
  double lane_m = 0.0;
  try {
    if (options.behaviour == "mapbuild") {
      MapBuildingConfig config;
      config.grid_resolution_m = options.grid_resolution_m;
      config.max_time_s = spec.max_duration_s;
      auto b = std::make_unique<MapBuildingBehaviour>(profile, config);
      builder = b.get();
      behaviour = std::move(b);
    } else {
      plan_grid = plannerGrid(map, profile);
      const auto s = plan_grid.worldToCell(start.position());
      if (!s || !plan_grid.isFree(*s)) {
        outcome.exit_code = kExitBehaviourFailed;
        outcome.error = "the start pose is outside the map or too close to an obstacle to plan";
        return outcome;
      }
      TravelPlan travel;
      if (options.behaviour == "goal") {
        const auto g = options.goal ? plan_grid.worldToCell(*options.goal) : std::nullopt;
        if (!g || !plan_grid.isFree(*g)) {
          outcome.exit_code = kExitBehaviourFailed;
          outcome.error = "the goal is outside the map or too close to an obstacle";
          return outcome;
        }
        const PlanResult raw = planAStar(plan_grid, *s, *g);
        if (!raw.found()) {
          outcome.exit_code = kExitBehaviourFailed;
          outcome.error = "no path to the goal (" + std::string(toString(raw.status)) + ")";
          return outcome;
        }
        const AmendResult amended = amendPath(plan_grid, raw.points, {});
        planned = amended.points;
        planned.front() = start.position();
        planned.back() = *options.goal;
        travel = makeTravelPlan(planned, start.theta, degToRad(15.0));
        extra["goal"] = {{"x", options.goal->x()}, {"y", options.goal->y()}};
        extra["plan"] = {{"astar_length_m", rounded(amended.length_before_m)},
                         {"astar_turns", amended.turns_before},
                         {"amended_length_m", rounded(amended.length_after_m)},
                         {"amended_turns", amended.turns_after},
                         {"amended_time_s", rounded(amended.time_after_s)},
                         {"astar_time_s", rounded(amended.time_before_s)},
                         {"segments", travel.segments.size()}};
      } else {
        CoverageOptions copt;
        lane_m = 2.0 * (profile.bodyRadius() - 0.02);  // overlap the lanes slightly
        copt.lane_cells = std::max(1, static_cast<int>(lane_m / plan_grid.resolution_m));
        lane_m = copt.lane_cells * plan_grid.resolution_m;
        const CoveragePlan cov = planCoverage(plan_grid, *s, copt);
        if (!cov.ok || cov.points.size() < 2) {
          outcome.exit_code = kExitBehaviourFailed;
          outcome.error = "no coverage path from the start";
          return outcome;
        }
        planned = cov.points;
        planned.insert(planned.begin(), start.position());
        travel = makeTravelPlan(planned, start.theta, degToRad(15.0));
        extra["plan"] = {{"pattern", "spiral"},
                         {"lane_m", rounded(lane_m)},
                         {"planned_coverage", rounded(cov.coverage)},
                         {"length_m", rounded(cov.length_m)},
                         {"turns", cov.turns},
                         {"segments", travel.segments.size()}};
      }
      behaviour = std::make_unique<TravelBehaviour>(profile, std::move(travel));
    }
  } catch (const std::exception& e) {
    outcome.exit_code = kExitBehaviourFailed;
    outcome.error = std::string("cannot set up the behaviour: ") + e.what();
    return outcome;
  }

  BehaviourScenarioResult result = runBehaviourScenario(spec, *behaviour);
  if (builder) {
    result.scenario.grid = builder->grid();  // the map the behaviour built (revised poses)
    try {
      const MapScore score = scoreMap(builder->grid(), map, start);
      extra["map_score"] = {{"precision", rounded(score.precision)},
                            {"recall", rounded(score.recall)},
                            {"f1", rounded(score.f1)},
                            {"resolution_m", score.resolution_m},
                            {"tolerance_cells", MapScoreOptions{}.tolerance_cells},
                            {"built_cells", score.built_cells},
                            {"truth_cells", score.truth_cells}};
    } catch (const std::exception& e) {
      // No ground truth to score against (e.g. a start inside a wall): say so, keep the run.
      extra["map_score"] = {{"error", e.what()}};
    }
    extra["map_building"] = {
        {"indices", builder->allIndices().size()},
        {"obstacles", builder->obstacleCount()},
        {"first_wall_was_obstacle", builder->firstWallWasObstacle()},
        {"outline_area_m2",
         builder->outline() ? rounded(-builder->outline()->signed_area_m2) : 0.0},
        {"heading_corrections", builder->headingCorrections()},
        {"interior_targets", builder->interiorTargetsVisited()}};
    planned = builder->allIndices();
  } else {
    extra["coverage"] =
        lane_m > 0.0
            ? rounded(executedCoverage(plan_grid, start, result.scenario.trajectory, 0.5 * lane_m))
            : 0.0;
    if (options.behaviour == "goal") {
      const Vec2 end = result.scenario.metrics.final_truth.position();
      extra["goal_error_m"] = rounded((end - *options.goal).norm());
      extra.erase("coverage");
    }
  }

  const ScenarioRunInfo info{options.map.filename().string(), profile.name, options.seed};
  const WriteOutputsResult written = writeScenarioOutputs(result.scenario, info, options.out);
  outcome.written = written.written;
  if (!written.error.empty()) {
    outcome.exit_code = kExitFiles;
    outcome.error = written.error;
    return outcome;
  }
  const auto write = [&](const char* name, const std::string& text) {
    const auto path = options.out / name;
    if (const auto err = writeFileAtomically(path, text)) {
      outcome.exit_code = kExitFiles;
      outcome.error = *err;
      return false;
    }
    outcome.written.push_back(path);
    return true;
  };
  if (!write("metrics.json", behaviourMetricsJson(result, info, extra)))
    return outcome;
  if (!write(builder ? "indices.csv" : "plan.csv",
             pointsCsv(planned, builder ? "index_x_m,index_y_m" : "x_m,y_m")))
    return outcome;

  const BehaviourMetrics& b = result.behaviour;
  char line[512];
  std::snprintf(line, sizeof line, "%s %s after %.1f s simulated (%.2f s wall), %.2f m, %d turns%s",
                b.behaviour.c_str(), b.failed ? "FAILED" : "finished",
                result.scenario.metrics.duration_s, b.wall_clock_s,
                result.scenario.metrics.distance_travelled_m, b.turns,
                extra.contains("map_score") && extra["map_score"].contains("f1")
                    ? (", F1 " + std::to_string(extra["map_score"]["f1"].get<double>())).c_str()
                    : "");
  outcome.summary = std::string(line) + ": " + b.message;
  if (b.failed)
    outcome.exit_code = kExitBehaviourFailed;
  return outcome;
}

}  // namespace irgs::app
