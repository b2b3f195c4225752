#pragma once
// Conservative (supercover) traversal of the cells a straight segment passes through.
//
// Coordinates are continuous cell coordinates: cell (c, r) covers [c, c+1) x [r, r+1). Every
// cell whose interior the segment crosses is visited in order from a to b; where the segment
// passes exactly through a cell corner, both cells beside the corner are visited too, so a
// segment never slips diagonally between two blocked cells (the same rule as A*'s "no corner
// cutting").

#include <cmath>
#include <cstdlib>

#include "core/mapping/occupancy_grid.hpp"

namespace irgs {

// Calls visit(Cell) for each cell; stops early when visit returns false. Returns false when
// stopped early. Non-finite coordinates visit nothing and return false.
template <class Visit>
bool forEachCellOnSegment(double x0, double y0, double x1, double y1, Visit&& visit) {
  if (!std::isfinite(x0) || !std::isfinite(y0) || !std::isfinite(x1) || !std::isfinite(y1))
    return false;
  int c = static_cast<int>(std::floor(x0));
  int r = static_cast<int>(std::floor(y0));
  const int c_end = static_cast<int>(std::floor(x1));
  const int r_end = static_cast<int>(std::floor(y1));
  const double dx = x1 - x0, dy = y1 - y0;
  const int step_c = dx > 0 ? 1 : -1, step_r = dy > 0 ? 1 : -1;
  // Parameter t in [0, 1] at the next vertical / horizontal cell border, and per-cell increment.
  constexpr double kInf = 1e300;
  double t_max_c = kInf, t_max_r = kInf, t_delta_c = kInf, t_delta_r = kInf;
  if (dx != 0.0) {
    const double border = dx > 0 ? std::floor(x0) + 1.0 : std::floor(x0);
    t_max_c = (border - x0) / dx;
    t_delta_c = 1.0 / std::abs(dx);
  }
  if (dy != 0.0) {
    const double border = dy > 0 ? std::floor(y0) + 1.0 : std::floor(y0);
    t_max_r = (border - y0) / dy;
    t_delta_r = 1.0 / std::abs(dy);
  }
  if (!visit(Cell{c, r}))
    return false;
  // Bounded by the number of cells between the end points (guards against rounding).
  const long max_steps =
      std::labs(static_cast<long>(c_end) - c) + std::labs(static_cast<long>(r_end) - r) + 2;
  constexpr double kCornerEps = 1e-9;
  for (long step = 0; step < max_steps && (c != c_end || r != r_end); ++step) {
    const double diff = t_max_c - t_max_r;
    if (std::abs(diff) <= kCornerEps) {
      // Through a corner: both side cells, then the diagonal one.
      if (t_max_c > 1.0)
        break;
      if (!visit(Cell{c + step_c, r}) || !visit(Cell{c, r + step_r}))
        return false;
      c += step_c;
      r += step_r;
      t_max_c += t_delta_c;
      t_max_r += t_delta_r;
    } else if (diff < 0) {
      if (t_max_c > 1.0)
        break;
      c += step_c;
      t_max_c += t_delta_c;
    } else {
      if (t_max_r > 1.0)
        break;
      r += step_r;
      t_max_r += t_delta_r;
    }
    if (!visit(Cell{c, r}))
      return false;
  }
  return true;
}

}  // namespace irgs
