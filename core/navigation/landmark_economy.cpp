#include "core/navigation/landmark_economy.hpp"

#include <cmath>
#include <set>
#include <stdexcept>
#include <utility>

namespace irgs {

namespace {

// True when (x, y) lies in a corridor: within half a width of a grid line, inside the floor.
bool inCorridor(const CorridorFloorSpec& f, double x, double y) {
  const double h = 0.5 * f.corridor_width_m;
  const double w = f.cols * f.block_m, d = f.rows * f.block_m;
  if (x < -h || x > w + h || y < -h || y > d + h)
    return false;
  const auto nearLine = [&](double v) {
    const double k = std::round(v / f.block_m);
    return std::abs(v - k * f.block_m) <= h;
  };
  return nearLine(x) || nearLine(y);
}

}  // namespace

EconomyRow landmarkEconomy(const CorridorFloorSpec& floor, const EconomyParams& params) {
  if (floor.cols < 1 || floor.rows < 1 || !(floor.block_m > floor.corridor_width_m) ||
      !(floor.corridor_width_m > 0.0) || !(params.marker_cell_m > 0.0) ||
      !(params.light_spacing_m > 0.0) || !(params.raster_m > 0.0))
    throw std::invalid_argument("landmarkEconomy: bad floor or parameters");
  EconomyRow row;
  row.floor = floor;
  const double h = 0.5 * floor.corridor_width_m;
  const double x0 = -h, y0 = -h;
  const double w = floor.cols * floor.block_m + 2 * h, d = floor.rows * floor.block_m + 2 * h;
  const auto nx = static_cast<long>(std::ceil(w / params.raster_m));
  const auto ny = static_cast<long>(std::ceil(d / params.raster_m));
  std::set<std::pair<long, long>> cells;
  long free_cells = 0;
  for (long j = 0; j < ny; ++j) {
    for (long i = 0; i < nx; ++i) {
      const double x = x0 + (static_cast<double>(i) + 0.5) * params.raster_m;
      const double y = y0 + (static_cast<double>(j) + 0.5) * params.raster_m;
      if (!inCorridor(floor, x, y))
        continue;
      ++free_cells;
      cells.emplace(static_cast<long>(std::floor((x - x0) / params.marker_cell_m)),
                    static_cast<long>(std::floor((y - y0) / params.marker_cell_m)));
    }
  }
  row.free_area_m2 = static_cast<double>(free_cells) * params.raster_m * params.raster_m;
  row.artificial_markers = static_cast<int>(cells.size());
  row.nodes = (floor.cols + 1) * (floor.rows + 1);
  row.edges = floor.cols * (floor.rows + 1) + floor.rows * (floor.cols + 1);
  row.mixed_markers = row.nodes;
  const double lit = floor.block_m - 2.0 * params.node_clear_m;
  const int per_edge =
      lit >= 0.0 ? static_cast<int>(std::floor(lit / params.light_spacing_m)) + 1 : 0;
  row.mixed_lights = per_edge * row.edges;
  return row;
}

std::vector<CorridorFloorSpec> defaultEconomyFloors() {
  std::vector<CorridorFloorSpec> floors;
  for (const auto& [c, r] :
       std::vector<std::pair<int, int>>{{1, 1}, {2, 1}, {2, 2}, {3, 2}, {3, 3}, {4, 3}})
    floors.push_back({c, r, 4.0, 2.0});
  return floors;
}

}  // namespace irgs
