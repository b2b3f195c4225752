#include "core/mission/interior_targets.hpp"

#include <algorithm>
#include <cmath>

#include "core/planning/nearest_search.hpp"
#include "core/planning/path_amendment.hpp"

namespace irgs {
namespace {

constexpr double kExploreFree = 0.3;       // long-range knowledge grid: free below this
constexpr float kOccupiedLogOdds = 0.62f;  // p = 0.65
constexpr double kObstacleReach_m = 0.25;  // beyond the inflation: an obstacle "within reach"
constexpr int kFrontierUnknownCells = 4;   // of the 5 x 5 neighbourhood

int floorDiv(int a, int b) {
  return a >= 0 ? a / b : -((-a + b - 1) / b);
}

enum class Known : std::uint8_t { kUnknown, kFree, kOccupied };

// The coarse view: one Known per coarse cell over the observed part of the grid, with a cell of
// margin all round, and the planning grid of it (occupied inflated, unknown blocked).
struct CoarseView {
  PlanningGrid grid;
  std::vector<Known> known;
  Known at(const Cell& c) const { return known[grid.index(c)]; }
};

CoarseView coarseView(const OccupancyGrid& fine, const OccupancyGrid& explore,
                      const InteriorSearchConfig& config) {
  CoarseView view;
  const double res = fine.resolution_m();
  const int f = std::max(1, static_cast<int>(std::lround(config.cell_m / res)));
  const double cell = f * res;
  const OccupancyGrid::CellRect rect = fine.observedCellRect();
  const int c0 = floorDiv(rect.col0, f) - 1, r0 = floorDiv(rect.row0, f) - 1;
  const int w = floorDiv(rect.col1, f) - c0 + 2, h = floorDiv(rect.row1, f) - r0 + 2;
  view.grid = PlanningGrid::freeGrid(w, h, cell, Vec2(c0 * cell, r0 * cell));
  std::vector<float> values;
  fine.copyLogOdds(rect, values);
  std::vector<int> observed(view.grid.cellCount(), 0), occupied(view.grid.cellCount(), 0);
  for (int r = 0; r < rect.height(); ++r)
    for (int c = 0; c < rect.width(); ++c) {
      const float v = values[static_cast<std::size_t>(r * rect.width() + c)];
      if (std::isnan(v))
        continue;
      const std::size_t k =
          view.grid.index({floorDiv(rect.col0 + c, f) - c0, floorDiv(rect.row0 + r, f) - r0});
      ++observed[k];
      if (v > kOccupiedLogOdds)
        ++occupied[k];
    }
  view.known.assign(view.grid.cellCount(), Known::kUnknown);
  for (std::size_t k = 0; k < view.known.size(); ++k)
    view.known[k] = occupied[k] >= 2 ? Known::kOccupied
                                     : (observed[k] * 2 >= f * f ? Known::kFree : Known::kUnknown);
  // Free space seen at long range is known too: no need to drive within the mapping range of
  // every open spot. Obstacles still come from the mapping grid only.
  if (config.explore_range_m > 0.0)
    for (std::size_t k = 0; k < view.known.size(); ++k) {
      if (view.known[k] != Known::kUnknown)
        continue;
      const Cell e = explore.cellAt(view.grid.cellCentre(view.grid.cellOf(k)));
      if (explore.observed(e) && explore.probability(e) < kExploreFree)
        view.known[k] = Known::kFree;
    }
  // Blocked for travel: occupied grown by the inflation; unknown.
  const int rad = static_cast<int>(std::ceil(config.inflate_m / cell));
  for (std::size_t k = 0; k < view.known.size(); ++k) {
    const Cell c = view.grid.cellOf(k);
    if (view.known[k] == Known::kUnknown)
      view.grid.setBlocked(c, true);
    if (view.known[k] != Known::kOccupied)
      continue;
    for (int dr = -rad; dr <= rad; ++dr)
      for (int dc = -rad; dc <= rad; ++dc) {
        const Cell m{c.col + dc, c.row + dr};
        if (view.grid.inside(m) && std::hypot(dc, dr) * cell <= config.inflate_m + 0.5 * cell)
          view.grid.setBlocked(m, true);
      }
  }
  return view;
}

}  // namespace

std::optional<InteriorTarget> chooseInteriorTarget(const Pose2& pose, const OccupancyGrid& grid,
                                                   const OccupancyGrid& explore_grid,
                                                   const ExploredRecord& record,
                                                   const InteriorSearchConfig& config) {
  if (!record.outline() || grid.observedCellRect().empty())
    return std::nullopt;
  CoarseView view = coarseView(grid, explore_grid, config);
  const double cell = view.grid.resolution_m;
  const std::optional<Cell> robot = view.grid.worldToCell(pose.position());
  if (!robot)
    return std::nullopt;
  view.grid.setBlocked(*robot, false);  // the search starts where the robot is, whatever it is
  // A robot that ended a loop beside an obstacle stands inside its inflated band: known free
  // cells that near it stay passable, so it can plan its way out instead of finding nothing.
  for (std::size_t k = 0; k < view.known.size(); ++k) {
    const Cell c = view.grid.cellOf(k);
    if (view.known[k] == Known::kFree &&
        std::hypot(c.col - robot->col, c.row - robot->row) * cell <= config.inflate_m + cell)
      view.grid.setBlocked(c, false);
  }
  const double near_m = config.inflate_m + kObstacleReach_m;
  const int near = static_cast<int>(std::ceil(near_m / cell));
  InteriorTarget target;
  const auto is_goal = [&](const Cell& c) {
    const Vec2 p = view.grid.cellCentre(c);
    const bool inside = record.insideOutline(p);
    // Beyond the outline (another room through a doorway the follower passed as a gap, or space
    // the first loop cut off) only frontiers count: obstacles there are mapped as they are
    // passed, not circumnavigated.
    if ((!inside && !config.beyond_outline) || record.listed(p))
      return false;
    target = {};
    target.position = p;
    for (int dr = -near; dr <= near && inside; ++dr)
      for (int dc = -near; dc <= near; ++dc) {
        const Cell m{c.col + dc, c.row + dr};
        if (!view.grid.inside(m) || view.at(m) != Known::kOccupied)
          continue;
        const Vec2 o = view.grid.cellCentre(m);
        if ((o - p).norm() > near_m || !record.insideOutline(o) || record.explained(o) ||
            record.listed(o) || record.visitedOften(o))
          continue;
        target.obstacle = true;
        target.obstacle_point = o;
        return true;
      }
    int unknown = 0;
    for (int dr = -2; dr <= 2; ++dr)
      for (int dc = -2; dc <= 2; ++dc) {
        const Cell m{c.col + dc, c.row + dr};
        if (view.grid.inside(m) && view.at(m) == Known::kUnknown &&
            (config.beyond_outline || record.insideOutline(view.grid.cellCentre(m))))
          ++unknown;
      }
    return unknown >= kFrontierUnknownCells;
  };
  const PlanResult plan = planToNearest(view.grid, *robot, is_goal);
  if (!plan.found())
    return std::nullopt;
  std::vector<Vec2> cells = plan.points;
  cells.front() = pose.position();
  target.path = compressPath(cells);
  return target;
}

}  // namespace irgs
