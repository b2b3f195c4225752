#include "app/gui/planning_tasks.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <stdexcept>
#include <utility>

namespace irgs::gui {
namespace {

PlanningGridOptions gridOptions(double radius_m) {
  PlanningGridOptions options;
  options.robot_radius_m = radius_m;
  options.unknown_is_blocked = true;
  return options;
}

void checkSettings(const PlanningSettings& s, double body_radius_m) {
  if (!std::isfinite(s.resolution_m) || s.resolution_m <= 0.0)
    throw std::invalid_argument("planning resolution must be finite and positive");
  if (!std::isfinite(s.clearance_m) || s.clearance_m < 0.0)
    throw std::invalid_argument("planning clearance must be finite and non-negative");
  if (!std::isfinite(body_radius_m) || body_radius_m < 0.0)
    throw std::invalid_argument("robot radius must be finite and non-negative");
}

// The free cell nearest to p within max_m (p's own cell first), or nothing.
std::optional<Cell> nearestFree(const PlanningGrid& grid, const Vec2& p, double max_m) {
  const auto cell = grid.worldToCell(p);
  if (!cell)
    return std::nullopt;
  if (grid.isFree(*cell))
    return cell;
  const int reach = static_cast<int>(std::ceil(max_m / grid.resolution_m));
  std::optional<Cell> best;
  double best_d = max_m;
  for (int dr = -reach; dr <= reach; ++dr) {
    for (int dc = -reach; dc <= reach; ++dc) {
      const Cell c{cell->col + dc, cell->row + dr};
      if (!grid.isFree(c))
        continue;
      const double d = (grid.cellCentre(c) - p).norm();
      if (d <= best_d) {
        best_d = d;
        best = c;
      }
    }
  }
  return best;
}

double elapsedSince(const std::function<double()>& now_s, double t0) {
  return now_s ? std::max(0.0, now_s() - t0) : 0.0;
}

}  // namespace

PlanningGrids gridsFromWorld(const WorldMap& map, double body_radius_m,
                             const PlanningSettings& settings) {
  checkSettings(settings, body_radius_m);
  PlanningGrids grids;
  grids.source = "map";
  grids.raw = planningGridFromWorld(map, settings.resolution_m, gridOptions(0.0));
  grids.inflated = inflate(grids.raw, body_radius_m + settings.clearance_m);
  return grids;
}

PlanningGrids gridsFromOccupancy(const OccupancyGrid& grid, double body_radius_m,
                                 const PlanningSettings& settings, const std::string& name) {
  checkSettings(settings, body_radius_m);
  PlanningGrids grids;
  grids.source = name;
  grids.raw = planningGridFromOccupancy(grid, gridOptions(0.0));
  grids.inflated = inflate(grids.raw, body_radius_m + settings.clearance_m);
  return grids;
}

GoalPreview previewGoal(const PlanningGrids& grids, const Pose2& robot, const Vec2& goal,
                        const PlanningSettings& settings, const std::function<double()>& now_s,
                        const std::function<bool()>& cancelled) {
  GoalPreview preview;
  const double t0 = now_s ? now_s() : 0.0;
  const PlanningGrid& grid = grids.inflated;
  if (grid.empty()) {
    preview.error = "nothing to plan on: the " + grids.source + " is empty";
    return preview;
  }
  if (!std::isfinite(goal.x()) || !std::isfinite(goal.y())) {
    preview.error = "the goal is not a finite point";
    return preview;
  }
  const auto start = nearestFree(grid, robot.position(), settings.goal_snap_m);
  if (!start) {
    preview.error = grid.worldToCell(robot.position())
                        ? "the robot is too close to an obstacle to plan from"
                        : "the robot is outside the " + grids.source;
    return preview;
  }
  const auto goal_cell = nearestFree(grid, goal, settings.goal_snap_m);
  if (!goal_cell) {
    preview.error = grid.worldToCell(goal)
                        ? "the goal is on or too close to an obstacle for the robot"
                        : "the goal is outside the " + grids.source;
    return preview;
  }
  const bool goal_free = grid.worldToCell(goal) == goal_cell;
  preview.goal = goal_free ? goal : grid.cellCentre(*goal_cell);
  if (!goal_free)
    preview.error = "goal moved off the obstacle margin";

  AStarOptions options;
  options.budget.max_expansions = settings.max_expansions;
  if (now_s && settings.budget_s > 0.0) {
    options.budget.max_time_s = settings.budget_s;
    options.budget.now_s = now_s;
  }
  options.budget.cancelled = cancelled;
  options.budget.check_interval = 256;
  const PlanResult raw = AStarPlanner().plan(grid, *start, *goal_cell, options);
  preview.status = raw.status;
  preview.expansions = raw.expansions;
  if (raw.status != PlanStatus::kFound && raw.status != PlanStatus::kPartial) {
    preview.error = std::string("no path: ") + std::string(toString(raw.status));
    preview.planning_time_s = elapsedSince(now_s, t0);
    return preview;
  }
  if (raw.status == PlanStatus::kPartial) {
    preview.error = "planning budget ran out: the path ends at the cell nearest the goal";
    preview.goal = raw.points.back();
  }
  const AmendResult amended = amendPath(grid, raw.points, {}, [&] {
    AmendOptions a;
    a.turn_quantum_rad = settings.turn_quantum_rad;
    a.time_model = settings.time_model;
    return a;
  }());
  // Both paths run from the robot itself to the goal itself (not the cell centres).
  auto endsAtRobotAndGoal = [&](std::vector<Vec2> points) {
    if (points.empty())
      points.push_back(robot.position());
    points.front() = robot.position();
    if (raw.status == PlanStatus::kFound) {
      if (points.size() < 2)
        points.push_back(preview.goal);
      points.back() = preview.goal;
    }
    return compressPath(points);
  };
  preview.raw = endsAtRobotAndGoal(raw.points);
  preview.amended = endsAtRobotAndGoal(amended.points);
  preview.raw_turns = countTurns(preview.raw);
  preview.amended_turns = countTurns(preview.amended);
  preview.raw_length_m = pathLength(preview.raw);
  preview.amended_length_m = pathLength(preview.amended);
  preview.raw_time_s = travelTime(preview.raw, settings.time_model, robot.theta);
  preview.amended_time_s = travelTime(preview.amended, settings.time_model, robot.theta);
  preview.travel = makeTravelPlan(preview.amended, robot.theta, settings.turn_quantum_rad);
  preview.ok = true;
  preview.planning_time_s = elapsedSince(now_s, t0);
  return preview;
}

PlanningGrid cropGrid(const PlanningGrid& grid, const Box2& box) {
  if (grid.empty() || box.empty())
    return {};
  const double res = grid.resolution_m;
  // Cells whose centre lies in the box: col >= (min - origin)/res - 0.5, col <= (max - ...)
  const int c0 =
      std::max(0, static_cast<int>(std::ceil((box.min.x() - grid.origin.x()) / res - 0.5)));
  const int r0 =
      std::max(0, static_cast<int>(std::ceil((box.min.y() - grid.origin.y()) / res - 0.5)));
  const int c1 = std::min(
      grid.width - 1, static_cast<int>(std::floor((box.max.x() - grid.origin.x()) / res - 0.5)));
  const int r1 = std::min(
      grid.height - 1, static_cast<int>(std::floor((box.max.y() - grid.origin.y()) / res - 0.5)));
  if (c1 < c0 || r1 < r0)
    return {};
  PlanningGrid out =
      PlanningGrid::freeGrid(c1 - c0 + 1, r1 - r0 + 1, res, grid.origin + Vec2(c0 * res, r0 * res));
  for (int r = 0; r < out.height; ++r) {
    for (int c = 0; c < out.width; ++c)
      out.blocked[out.index({c, r})] = grid.blocked[grid.index({c0 + c, r0 + r})];
  }
  return out;
}

CoveragePreview previewCoverage(const PlanningGrids& grids, const Pose2& robot, const Box2& region,
                                CoveragePattern pattern, double lane_m,
                                const PlanningSettings& settings,
                                const std::function<double()>& now_s) {
  CoveragePreview preview;
  if (grids.inflated.empty()) {
    preview.error = "nothing to plan on: the " + grids.source + " is empty";
    return preview;
  }
  if (!std::isfinite(lane_m) || lane_m <= 0.0) {
    preview.error = "the lane width must be positive";
    return preview;
  }
  preview.region_inflated = cropGrid(grids.inflated, region);
  preview.region_raw = cropGrid(grids.raw, region);
  if (preview.region_inflated.empty() ||
      preview.region_inflated.blockedCount() == preview.region_inflated.cellCount()) {
    preview.error = "the region holds no place the robot fits";
    return preview;
  }
  const PlanningGrid& sub = preview.region_inflated;
  preview.region.extend(sub.origin);
  preview.region.extend(sub.origin +
                        Vec2(sub.width * sub.resolution_m, sub.height * sub.resolution_m));

  // Enter the region at its free cell nearest the robot that the robot can reach.
  std::vector<std::pair<double, Cell>> candidates;
  for (int r = 0; r < sub.height; ++r) {
    for (int c = 0; c < sub.width; ++c) {
      if (sub.isFree({c, r}))
        candidates.push_back({(sub.cellCentre({c, r}) - robot.position()).norm(), Cell{c, r}});
    }
  }
  std::sort(candidates.begin(), candidates.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  GoalPreview approach;
  bool entered = false;
  for (std::size_t i = 0; i < std::min<std::size_t>(candidates.size(), 8) && !entered; i += 1) {
    const Vec2 entry = sub.cellCentre(candidates[i].second);
    preview.region_start = candidates[i].second;
    if ((entry - robot.position()).norm() < sub.resolution_m) {
      entered = true;
      approach = {};
      approach.amended = {robot.position()};
      break;
    }
    approach = previewGoal(grids, robot, entry, settings, now_s);
    entered = approach.ok && approach.status == PlanStatus::kFound;
  }
  if (!entered) {
    preview.error = "the robot cannot reach the region";
    return preview;
  }
  CoverageOptions options;
  options.pattern = pattern;
  options.lane_cells = std::max(1, static_cast<int>(std::lround(lane_m / sub.resolution_m)));
  preview.coverage = planCoverage(sub, preview.region_start, options);
  if (!preview.coverage.ok || preview.coverage.points.empty()) {
    preview.error = "no coverage path in the region";
    return preview;
  }
  preview.approach = approach.amended;
  preview.path = preview.approach;
  const auto& lanes = preview.coverage.points;
  preview.path.insert(preview.path.end(), lanes.begin() + 1, lanes.end());
  if (preview.path.size() < 2)
    preview.path.push_back(lanes.front());
  preview.path = compressPath(preview.path);
  preview.travel = makeTravelPlan(preview.path, robot.theta, settings.turn_quantum_rad);
  preview.time_s =
      preview.path.size() >= 2 ? travelTime(preview.path, settings.time_model, robot.theta) : 0.0;
  preview.ok = true;
  return preview;
}

CoverageSweep::CoverageSweep(PlanningGrid region_raw, const PlanningGrid& region_inflated,
                             const Cell& start, double body_radius_m)
    : raw_(std::move(region_raw)) {
  if (raw_.width != region_inflated.width || raw_.height != region_inflated.height ||
      raw_.resolution_m != region_inflated.resolution_m || raw_.origin != region_inflated.origin)
    throw std::invalid_argument("CoverageSweep: raw and inflated grids differ in geometry");
  if (!std::isfinite(body_radius_m) || body_radius_m < 0.0)
    throw std::invalid_argument("CoverageSweep: body radius must be finite and non-negative");
  state_.assign(raw_.cellCount(), 0);
  const int reach = static_cast<int>(std::floor(body_radius_m / raw_.resolution_m));
  for (int dr = -reach; dr <= reach; ++dr) {
    for (int dc = -reach; dc <= reach; ++dc) {
      if (std::hypot(dc, dr) * raw_.resolution_m <= body_radius_m)
        disc_.push_back({dc, dr});
    }
  }
  if (!region_inflated.isFree(start))
    return;
  // Robot-centre cells reachable from the start (4-connected flood; the planner's diagonal
  // moves without corner cutting connect the same cells).
  std::vector<std::uint8_t> seen(raw_.cellCount(), 0);
  std::deque<Cell> queue{start};
  seen[raw_.index(start)] = 1;
  while (!queue.empty()) {
    const Cell c = queue.front();
    queue.pop_front();
    for (const Cell& d : disc_) {
      const Cell n{c.col + d.col, c.row + d.row};
      if (raw_.isFree(n) && state_[raw_.index(n)] == 0) {
        state_[raw_.index(n)] = 1;
        ++sweepable_count_;
      }
    }
    for (const Cell& step : {Cell{1, 0}, Cell{-1, 0}, Cell{0, 1}, Cell{0, -1}}) {
      const Cell n{c.col + step.col, c.row + step.row};
      if (region_inflated.isFree(n) && !seen[raw_.index(n)]) {
        seen[raw_.index(n)] = 1;
        queue.push_back(n);
      }
    }
  }
}

void CoverageSweep::addPosition(const Vec2& p) {
  if (state_.empty() || !std::isfinite(p.x()) || !std::isfinite(p.y()))
    return;
  const double res = raw_.resolution_m;
  const Vec2 local = (p - raw_.origin) / res;
  const int cc = static_cast<int>(std::floor(local.x()));
  const int cr = static_cast<int>(std::floor(local.y()));
  // Cells far outside cannot be touched: skip the disc loop.
  const int margin = disc_.empty() ? 0 : std::abs(disc_.front().col) + 1;
  if (cc < -margin || cr < -margin || cc > raw_.width + margin || cr > raw_.height + margin)
    return;
  for (const Cell& d : disc_) {
    const Cell n{cc + d.col, cr + d.row};
    if (!raw_.inside(n))
      continue;
    std::uint8_t& s = state_[raw_.index(n)];
    if (s == 1) {
      s = 2;
      ++swept_count_;
    }
  }
}

double CoverageSweep::coverage() const {
  return sweepable_count_ == 0
             ? 0.0
             : static_cast<double>(swept_count_) / static_cast<double>(sweepable_count_);
}

}  // namespace irgs::gui
