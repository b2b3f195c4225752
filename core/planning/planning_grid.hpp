#pragma once
// A binary traversability grid for the planners: one byte per cell, 1 = blocked, 0 = free.
//
// Cell (col, row) covers world [origin.x + col*res, origin.x + (col+1)*res) x [origin.y +
// row*res, ...): row 0 is the smallest y, storage is row-major (index = row * width + col), the
// same convention as RasterMap. The grid is a plain value. Builders convert the project's maps
// (RasterMap, OccupancyGrid, WorldMap) and inflate them by the robot radius with an exact
// Euclidean distance transform (distance_transform.hpp), so that a robot whose centre stays on
// free cells of the inflated grid keeps its disc off the obstacles.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/geometry/types.hpp"
#include "core/mapping/occupancy_grid.hpp"
#include "core/world/raster_map.hpp"
#include "core/world/world_map.hpp"

namespace irgs {

struct PlanningGrid {
  int width = 0;
  int height = 0;
  double resolution_m = 0.05;
  Vec2 origin = Vec2::Zero();         // world position of the lower-left corner of cell (0, 0)
  std::vector<std::uint8_t> blocked;  // width * height, 1 = blocked

  // An all-free grid. Throws std::invalid_argument for negative sizes, a non-finite or
  // non-positive resolution, a non-finite origin or more than kMaxCells cells.
  static PlanningGrid freeGrid(int width, int height, double resolution_m,
                               const Vec2& origin = Vec2::Zero());
  // 2^31 - 1: cell indices fit an int32 and a uint32 with room for a sentinel.
  static constexpr std::int64_t kMaxCells = (std::int64_t{1} << 31) - 1;

  bool empty() const { return width <= 0 || height <= 0; }
  std::size_t cellCount() const {
    return static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  }
  bool inside(const Cell& c) const {
    return c.col >= 0 && c.row >= 0 && c.col < width && c.row < height;
  }
  std::size_t index(const Cell& c) const {
    return static_cast<std::size_t>(c.row) * static_cast<std::size_t>(width) +
           static_cast<std::size_t>(c.col);
  }
  Cell cellOf(std::size_t index) const {
    return {static_cast<int>(index % static_cast<std::size_t>(width)),
            static_cast<int>(index / static_cast<std::size_t>(width))};
  }
  // False outside the grid.
  bool isFree(const Cell& c) const { return inside(c) && blocked[index(c)] == 0; }
  void setBlocked(const Cell& c, bool value) { blocked[index(c)] = value ? 1 : 0; }
  Vec2 cellCentre(const Cell& c) const {
    return {origin.x() + (c.col + 0.5) * resolution_m, origin.y() + (c.row + 0.5) * resolution_m};
  }
  // Cell containing p, or nothing when p is outside the grid or not finite.
  std::optional<Cell> worldToCell(const Vec2& p) const;
  std::size_t blockedCount() const;

  friend bool operator==(const PlanningGrid&, const PlanningGrid&) = default;
};

// How map values become blocked cells.
struct PlanningGridOptions {
  // RasterMap: a cell is blocked when its value (0..100) >= this.
  int raster_occupied_threshold = 65;
  // OccupancyGrid: a cell is blocked when its occupancy probability >= this.
  double occupied_probability = 0.65;
  // Unknown cells (raster -1, never-observed occupancy cells) are blocked when true.
  bool unknown_is_blocked = true;
  // Robot radius for inflation (0 = none), metres.
  double robot_radius_m = 0.0;
};

// What is wrong with the options (non-finite or negative radius, probability outside [0, 1],
// threshold outside 0..101), or nothing.
std::optional<std::string> planningGridOptionsError(const PlanningGridOptions& options);

// Blocks every cell whose centre lies within radius_m + res/2 of the centre of a blocked cell
// (exact Euclidean distance transform; the half cell accounts for the blocked cell's extent, so
// the rule is exact for obstacles along the axes and errs by at most 0.21 cells on diagonals).
// radius_m <= 0 returns the grid unchanged. Throws std::invalid_argument for a non-finite radius.
PlanningGrid inflate(const PlanningGrid& grid, double radius_m);

// Throws std::invalid_argument for invalid options or a raster whose cells do not match its
// size or whose resolution is not finite and positive. Inflates by options.robot_radius_m.
PlanningGrid planningGridFromRaster(const RasterMap& raster, const PlanningGridOptions& options);

// The observed part of the grid (observedCellRect), grown by margin_cells on every side (the
// margin is unknown, hence blocked when unknown_is_blocked). An empty grid gives an empty
// planning grid. Throws std::invalid_argument for invalid options or a negative margin.
PlanningGrid planningGridFromOccupancy(const OccupancyGrid& grid,
                                       const PlanningGridOptions& options, int margin_cells = 1);

// Rasterises the map's walls (every cell a wall piece passes through, supercover) and fills
// its obstacles (cells whose centre is inside a polygon), over the map's bounds grown by
// margin_m, at resolution_m; cells are free otherwise (options.unknown_is_blocked is not used).
// Throws std::invalid_argument for a non-finite or non-positive resolution, a negative margin,
// invalid options, an empty map or a grid beyond kMaxCells.
PlanningGrid planningGridFromWorld(const WorldMap& map, double resolution_m,
                                   const PlanningGridOptions& options, double margin_m = 0.1);

}  // namespace irgs
