#include "core/mapping/grid_ray.hpp"

#include <cmath>
#include <cstdlib>
#include <limits>
#include <stdexcept>

namespace irgs {

std::vector<Cell> traverseRay(const Vec2& from, const Vec2& to, double resolution_m) {
  if (!std::isfinite(resolution_m) || !(resolution_m > 0.0))
    throw std::invalid_argument("traverseRay: resolution_m must be finite and > 0");
  const OccupancyGrid frame(resolution_m);
  if (!frame.isAddressable(from) || !frame.isAddressable(to))
    throw std::invalid_argument("traverseRay: end points must be finite and addressable");
  const Cell start = frame.cellAt(from);
  const Cell end = frame.cellAt(to);
  const long steps_x = std::labs(static_cast<long>(end.col) - start.col);
  const long steps_y = std::labs(static_cast<long>(end.row) - start.row);
  if (steps_x + steps_y + 1 > kMaxRayCells)
    throw std::length_error("traverseRay: segment crosses more than kMaxRayCells cells");

  const Vec2 d = to - from;
  const int step_col = end.col > start.col ? 1 : -1;
  const int step_row = end.row > start.row ? 1 : -1;
  constexpr double kInf = std::numeric_limits<double>::infinity();
  // t in [0, 1] along the segment where the ray crosses the next vertical / horizontal cell
  // boundary (t_max), and how much t grows per cell along each axis (t_delta).
  const auto firstCrossing = [&](int cell, int step, double start_coord, double delta) {
    if (delta == 0.0)
      return kInf;
    const double boundary = (cell + (step > 0 ? 1.0 : 0.0)) * resolution_m;
    return (boundary - start_coord) / delta;
  };
  double t_max_x = firstCrossing(start.col, step_col, from.x(), d.x());
  double t_max_y = firstCrossing(start.row, step_row, from.y(), d.y());
  const double t_delta_x = d.x() == 0.0 ? kInf : resolution_m / std::abs(d.x());
  const double t_delta_y = d.y() == 0.0 ? kInf : resolution_m / std::abs(d.y());

  std::vector<Cell> cells;
  cells.reserve(static_cast<std::size_t>(steps_x + steps_y + 1));
  Cell c = start;
  cells.push_back(c);
  // The remaining step counts decide termination, so rounding in t can reorder a step near a
  // corner but never overshoot or miss the end cell.
  long left_x = steps_x, left_y = steps_y;
  while (left_x > 0 || left_y > 0) {
    if (left_y == 0 || (left_x > 0 && t_max_x <= t_max_y)) {
      c.col += step_col;
      t_max_x += t_delta_x;
      --left_x;
    } else {
      c.row += step_row;
      t_max_y += t_delta_y;
      --left_y;
    }
    cells.push_back(c);
  }
  return cells;
}

}  // namespace irgs
