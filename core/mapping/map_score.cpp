#include "core/mapping/map_score.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace irgs {
namespace {

// Marks every cell within Chebyshev distance r of a set cell (separable square dilation).
std::vector<std::uint8_t> dilate(const std::vector<std::uint8_t>& in, int w, int h, int r) {
  std::vector<std::uint8_t> tmp(in.size(), 0), out(in.size(), 0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (!in[static_cast<std::size_t>(y * w + x)])
        continue;
      for (int dx = std::max(0, x - r); dx <= std::min(w - 1, x + r); ++dx)
        tmp[static_cast<std::size_t>(y * w + dx)] = 1;
    }
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (!tmp[static_cast<std::size_t>(y * w + x)])
        continue;
      for (int dy = std::max(0, y - r); dy <= std::min(h - 1, y + r); ++dy)
        out[static_cast<std::size_t>(dy * w + x)] = 1;
    }
  return out;
}

}  // namespace

PlanningGrid trueSurfaceGrid(const WorldMap& map, const Pose2& start, double resolution_m) {
  PlanningGridOptions opt;
  opt.unknown_is_blocked = true;
  PlanningGrid solid = (map.raster && map.walls.empty() && map.obstacles.empty())
                           ? planningGridFromRaster(map.raster->raster, opt)
                           : planningGridFromWorld(map, resolution_m, opt, 0.2);
  const auto start_cell = solid.worldToCell(start.position());
  if (!start_cell || !solid.isFree(*start_cell))
    throw std::invalid_argument("trueSurfaceGrid: the start pose is not in the map's free space");
  // Flood fill the free space reachable from the start (4-connected).
  std::vector<std::uint8_t> reach(solid.cellCount(), 0);
  std::vector<std::size_t> stack{solid.index(*start_cell)};
  reach[stack.back()] = 1;
  const int w = solid.width, h = solid.height;
  while (!stack.empty()) {
    const Cell c = solid.cellOf(stack.back());
    stack.pop_back();
    const Cell nb[4] = {
        {c.col + 1, c.row}, {c.col - 1, c.row}, {c.col, c.row + 1}, {c.col, c.row - 1}};
    for (const Cell& n : nb) {
      if (!solid.isFree(n))
        continue;
      const std::size_t i = solid.index(n);
      if (!reach[i]) {
        reach[i] = 1;
        stack.push_back(i);
      }
    }
  }
  PlanningGrid surface = PlanningGrid::freeGrid(w, h, solid.resolution_m, solid.origin);
  for (int row = 0; row < h; ++row)
    for (int col = 0; col < w; ++col) {
      const Cell c{col, row};
      if (solid.isFree(c))
        continue;
      const Cell nb[4] = {{col + 1, row}, {col - 1, row}, {col, row + 1}, {col, row - 1}};
      for (const Cell& n : nb)
        if (solid.inside(n) && reach[solid.index(n)]) {
          surface.setBlocked(c, true);
          break;
        }
    }
  return surface;
}

MapScore scoreMap(const OccupancyGrid& built, const PlanningGrid& truth,
                  const MapScoreOptions& options) {
  if (options.tolerance_cells < 0)
    throw std::invalid_argument("scoreMap: tolerance_cells must be >= 0");
  if (!(options.occupied_probability > 0.0 && options.occupied_probability < 1.0))
    throw std::invalid_argument("scoreMap: occupied_probability must be in (0, 1)");
  MapScore score;
  score.resolution_m = truth.resolution_m;
  const int w = truth.width, h = truth.height;
  std::vector<std::uint8_t> built_cells(truth.cellCount(), 0);
  std::size_t built_outside = 0;  // occupied scoring cells beyond the truth grid: all wrong
  const float threshold = static_cast<float>(
      std::log(options.occupied_probability / (1.0 - options.occupied_probability)));
  const OccupancyGrid::CellRect rect = built.observedCellRect();
  std::vector<float> values;
  if (!rect.empty())
    built.copyLogOdds(rect, values);
  std::vector<std::pair<int, int>> outside_cells;
  for (int r = 0; r < rect.height(); ++r)
    for (int c = 0; c < rect.width(); ++c) {
      const float v = values[static_cast<std::size_t>(r * rect.width() + c)];
      if (!(v > threshold))
        continue;
      const Vec2 p = built.cellCentre({rect.col0 + c, rect.row0 + r});
      if (const auto cell = truth.worldToCell(p))
        built_cells[truth.index(*cell)] = 1;
      else
        outside_cells.emplace_back(static_cast<int>(std::floor(p.x() / truth.resolution_m)),
                                   static_cast<int>(std::floor(p.y() / truth.resolution_m)));
    }
  std::sort(outside_cells.begin(), outside_cells.end());
  built_outside = static_cast<std::size_t>(std::unique(outside_cells.begin(), outside_cells.end()) -
                                           outside_cells.begin());

  const auto near_truth = dilate(truth.blocked, w, h, options.tolerance_cells);
  const auto near_built = dilate(built_cells, w, h, options.tolerance_cells);
  std::size_t built_ok = 0, truth_ok = 0;
  for (std::size_t i = 0; i < truth.cellCount(); ++i) {
    if (built_cells[i]) {
      ++score.built_cells;
      built_ok += near_truth[i];
    }
    if (truth.blocked[i]) {
      ++score.truth_cells;
      truth_ok += near_built[i];
    }
  }
  score.built_cells += built_outside;
  score.precision = score.built_cells
                        ? static_cast<double>(built_ok) / static_cast<double>(score.built_cells)
                        : 0.0;
  score.recall = score.truth_cells
                     ? static_cast<double>(truth_ok) / static_cast<double>(score.truth_cells)
                     : 0.0;
  const double sum = score.precision + score.recall;
  score.f1 = sum > 0.0 ? 2.0 * score.precision * score.recall / sum : 0.0;
  return score;
}

MapScore scoreMap(const OccupancyGrid& built, const WorldMap& map, const Pose2& start,
                  const MapScoreOptions& options) {
  return scoreMap(built, trueSurfaceGrid(map, start, options.resolution_m), options);
}

}  // namespace irgs
