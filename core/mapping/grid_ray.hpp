#pragma once
// Traversal of grid cells along a straight segment, for ray-style sensors (infrared proximity,
// a single sonar ray) and for line-of-sight queries on the occupancy grid.

#include <vector>

#include "core/geometry/types.hpp"
#include "core/mapping/occupancy_grid.hpp"

namespace irgs {

// Cells crossed by the segment from -> to, in order, by the exact grid traversal of Amanatides
// & Woo (1987, "A fast voxel traversal algorithm", a DDA): the first cell contains `from`, the
// last contains `to`, consecutive cells share an edge, and the count is |dcol| + |drow| + 1.
// When the segment passes exactly through a cell corner the step along x is taken first.
// Cells follow OccupancyGrid::cellAt (cell (0, 0) has its lower-left corner at the origin).
// Throws std::invalid_argument for a non-finite point or resolution <= 0, std::length_error
// when the segment would cross more than kMaxRayCells cells.
inline constexpr long kMaxRayCells = 1L << 24;
std::vector<Cell> traverseRay(const Vec2& from, const Vec2& to, double resolution_m);

}  // namespace irgs
