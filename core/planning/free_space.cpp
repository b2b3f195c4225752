#include "core/planning/free_space.hpp"

#include <algorithm>
#include <cmath>

#include "core/planning/grid_line.hpp"

namespace irgs {

bool segmentIsFree(const PlanningGrid& grid, const Vec2& a, const Vec2& b) {
  if (grid.empty() || !a.allFinite() || !b.allFinite())
    return false;
  const Vec2 pa = (a - grid.origin) / grid.resolution_m, pb = (b - grid.origin) / grid.resolution_m;
  return forEachCellOnSegment(pa.x(), pa.y(), pb.x(), pb.y(),
                              [&grid](const Cell& c) { return grid.isFree(c); });
}

bool triangleIsFree(const PlanningGrid& grid, const Vec2& a, const Vec2& b, const Vec2& c) {
  if (!segmentIsFree(grid, a, b) || !segmentIsFree(grid, b, c) || !segmentIsFree(grid, c, a))
    return false;
  Box2 box;
  box.extend(a);
  box.extend(b);
  box.extend(c);
  // The edges are free and inside the grid, so the box is inside the grid too.
  const auto lo = grid.worldToCell(box.min);
  const auto hi = grid.worldToCell(box.max);
  if (!lo || !hi)
    return false;
  const double area = cross(b - a, c - a);
  if (area == 0.0)
    return true;  // degenerate: the edges cover it
  const double sign = area > 0.0 ? 1.0 : -1.0;
  for (int r = lo->row; r <= hi->row; ++r)
    for (int col = lo->col; col <= hi->col; ++col) {
      const Vec2 p = grid.cellCentre({col, r});
      const bool inside = sign * cross(b - a, p - a) >= 0.0 && sign * cross(c - b, p - b) >= 0.0 &&
                          sign * cross(a - c, p - c) >= 0.0;
      if (inside && !grid.isFree({col, r}))
        return false;
    }
  return true;
}

bool polylineIsFree(const PlanningGrid& grid, const std::vector<Vec2>& points) {
  if (points.empty())
    return false;
  if (points.size() == 1)
    return grid.worldToCell(points[0]).has_value() && grid.isFree(*grid.worldToCell(points[0]));
  for (std::size_t i = 1; i < points.size(); ++i)
    if (!segmentIsFree(grid, points[i - 1], points[i]))
      return false;
  return true;
}

}  // namespace irgs
