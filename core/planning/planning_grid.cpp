#include "core/planning/planning_grid.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/geometry/geometry_queries.hpp"
#include "core/planning/distance_transform.hpp"
#include "core/planning/grid_line.hpp"

namespace irgs {
namespace {

void requireValid(const PlanningGridOptions& options) {
  if (const auto error = planningGridOptionsError(options))
    throw std::invalid_argument("planning grid options: " + *error);
}

PlanningGrid finish(PlanningGrid grid, const PlanningGridOptions& options) {
  return inflate(grid, options.robot_radius_m);
}

}  // namespace

PlanningGrid PlanningGrid::freeGrid(int width, int height, double resolution_m,
                                    const Vec2& origin) {
  if (width < 0 || height < 0)
    throw std::invalid_argument("PlanningGrid: negative size");
  if (!std::isfinite(resolution_m) || resolution_m <= 0.0)
    throw std::invalid_argument("PlanningGrid: resolution must be finite and > 0");
  if (!origin.allFinite())
    throw std::invalid_argument("PlanningGrid: origin must be finite");
  if (static_cast<std::int64_t>(width) * height > kMaxCells)
    throw std::invalid_argument("PlanningGrid: too many cells");
  PlanningGrid g;
  g.width = width;
  g.height = height;
  g.resolution_m = resolution_m;
  g.origin = origin;
  g.blocked.assign(g.cellCount(), 0);
  return g;
}

std::optional<Cell> PlanningGrid::worldToCell(const Vec2& p) const {
  if (!p.allFinite())
    return std::nullopt;
  const double fx = (p.x() - origin.x()) / resolution_m;
  const double fy = (p.y() - origin.y()) / resolution_m;
  if (fx < 0.0 || fy < 0.0 || fx >= width || fy >= height)
    return std::nullopt;
  return Cell{std::min(static_cast<int>(fx), width - 1),
              std::min(static_cast<int>(fy), height - 1)};
}

std::size_t PlanningGrid::blockedCount() const {
  return static_cast<std::size_t>(
      std::count_if(blocked.begin(), blocked.end(), [](std::uint8_t b) { return b != 0; }));
}

std::optional<std::string> planningGridOptionsError(const PlanningGridOptions& options) {
  if (!std::isfinite(options.robot_radius_m) || options.robot_radius_m < 0.0)
    return "robot_radius_m must be finite and >= 0";
  if (!(options.occupied_probability >= 0.0 && options.occupied_probability <= 1.0))
    return "occupied_probability must be in [0, 1]";
  if (options.raster_occupied_threshold < 0 || options.raster_occupied_threshold > 101)
    return "raster_occupied_threshold must be in 0..101";
  return std::nullopt;
}

PlanningGrid inflate(const PlanningGrid& grid, double radius_m) {
  if (!std::isfinite(radius_m))
    throw std::invalid_argument("inflate: radius must be finite");
  if (radius_m <= 0.0 || grid.empty())
    return grid;
  const std::vector<double> d2 = squaredDistanceTransform(grid.blocked, grid.width, grid.height);
  const double reach_cells = radius_m / grid.resolution_m + 0.5;
  const double reach2 = reach_cells * reach_cells;
  PlanningGrid out = grid;
  for (std::size_t i = 0; i < d2.size(); ++i)
    if (d2[i] <= reach2)
      out.blocked[i] = 1;
  return out;
}

PlanningGrid planningGridFromRaster(const RasterMap& raster, const PlanningGridOptions& options) {
  requireValid(options);
  if (raster.width < 0 || raster.height < 0 ||
      raster.cells.size() != static_cast<std::size_t>(std::max(raster.width, 0)) *
                                 static_cast<std::size_t>(std::max(raster.height, 0)))
    throw std::invalid_argument("planningGridFromRaster: cells do not match the raster size");
  PlanningGrid g = PlanningGrid::freeGrid(raster.width, raster.height, raster.resolution_m,
                                          Vec2(raster.origin.x, raster.origin.y));
  for (std::size_t i = 0; i < raster.cells.size(); ++i) {
    const int v = raster.cells[i];
    const bool unknown = v < 0;
    g.blocked[i] =
        (unknown ? options.unknown_is_blocked : v >= options.raster_occupied_threshold) ? 1 : 0;
  }
  return finish(std::move(g), options);
}

PlanningGrid planningGridFromOccupancy(const OccupancyGrid& grid,
                                       const PlanningGridOptions& options, int margin_cells) {
  requireValid(options);
  if (margin_cells < 0)
    throw std::invalid_argument("planningGridFromOccupancy: negative margin");
  OccupancyGrid::CellRect rect = grid.observedCellRect();
  if (rect.empty())
    return PlanningGrid::freeGrid(0, 0, grid.resolution_m());
  rect.col0 -= margin_cells;
  rect.row0 -= margin_cells;
  rect.col1 += margin_cells;
  rect.row1 += margin_cells;
  const double res = grid.resolution_m();
  PlanningGrid g = PlanningGrid::freeGrid(rect.width(), rect.height(), res,
                                          Vec2(rect.col0 * res, rect.row0 * res));
  std::vector<float> log_odds;
  grid.copyLogOdds(rect, log_odds);
  // p >= p_occ  <=>  l >= log(p_occ / (1 - p_occ)); p_occ = 1 gives +inf (nothing blocked by
  // evidence unless clamped there), p_occ = 0 gives -inf (every observed cell blocked).
  const double p = options.occupied_probability;
  const double l_occ = p <= 0.0 ? -INFINITY : p >= 1.0 ? INFINITY : std::log(p / (1.0 - p));
  for (std::size_t i = 0; i < log_odds.size(); ++i) {
    const float l = log_odds[i];
    const bool unknown = std::isnan(l);
    g.blocked[i] = (unknown ? options.unknown_is_blocked : static_cast<double>(l) >= l_occ) ? 1 : 0;
  }
  return finish(std::move(g), options);
}

PlanningGrid planningGridFromWorld(const WorldMap& map, double resolution_m,
                                   const PlanningGridOptions& options, double margin_m) {
  requireValid(options);
  if (!std::isfinite(resolution_m) || resolution_m <= 0.0)
    throw std::invalid_argument("planningGridFromWorld: resolution must be finite and > 0");
  if (!std::isfinite(margin_m) || margin_m < 0.0)
    throw std::invalid_argument("planningGridFromWorld: margin must be finite and >= 0");
  Box2 box;
  for (const Segment& s : map.segments()) {
    box.extend(s.a);
    box.extend(s.b);
  }
  if (box.empty() || !box.min.allFinite() || !box.max.allFinite())
    throw std::invalid_argument("planningGridFromWorld: the map has no walls or obstacles");
  const Vec2 origin = box.min - Vec2::Constant(margin_m);
  const Vec2 size = box.size() + Vec2::Constant(2.0 * margin_m);
  const double w = std::ceil(size.x() / resolution_m), h = std::ceil(size.y() / resolution_m);
  if (w * h > static_cast<double>(PlanningGrid::kMaxCells) || w > 1e9 || h > 1e9)
    throw std::invalid_argument("planningGridFromWorld: grid too large for this resolution");
  PlanningGrid g = PlanningGrid::freeGrid(std::max(1, static_cast<int>(w)),
                                          std::max(1, static_cast<int>(h)), resolution_m, origin);
  const auto mark = [&g](const Cell& c) {
    if (g.inside(c))
      g.setBlocked(c, true);
    return true;
  };
  for (const Segment& s : map.segments()) {
    const Vec2 a = (s.a - origin) / resolution_m, b = (s.b - origin) / resolution_m;
    forEachCellOnSegment(a.x(), a.y(), b.x(), b.y(), mark);
  }
  for (const Obstacle& o : map.obstacles) {
    if (o.polygon.size() < 3)
      continue;
    Box2 ob;
    for (const Vec2& p : o.polygon)
      ob.extend(p);
    const auto lo = g.worldToCell(ob.min.cwiseMax(origin));
    const int c1 =
        std::min(g.width - 1, static_cast<int>((ob.max.x() - origin.x()) / resolution_m));
    const int r1 =
        std::min(g.height - 1, static_cast<int>((ob.max.y() - origin.y()) / resolution_m));
    if (!lo)
      continue;
    for (int r = lo->row; r <= r1; ++r)
      for (int c = lo->col; c <= c1; ++c)
        // (cells on an obstacle's outline are also covered by rasterising its edges)
        if (pointInPolygon(g.cellCentre({c, r}), o.polygon))
          g.setBlocked({c, r}, true);
  }
  return finish(std::move(g), options);
}

}  // namespace irgs
