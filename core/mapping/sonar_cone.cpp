#include "core/mapping/sonar_cone.hpp"

#include <algorithm>
#include <cmath>

// This file is compiled with -ffp-contract=off (core/mapping/CMakeLists.txt): the rasteriser
// and classify() must round every expression identically, which a fused multiply-add in one
// place and not the other would break.

namespace irgs {
namespace {

// The three tests of the criterion, written once and used by classify() and the rasteriser.
// In the beam: cross(u_r, d) >= 0 (d is counter-clockwise of the right edge)...
inline bool leftOfRightEdge(const SonarCone& cone, double dx, double dy) {
  return cone.right_edge.x() * dy - cone.right_edge.y() * dx >= 0.0;
}
// ...and cross(d, u_l) >= 0 (d is clockwise of the left edge). With a beam under pi the two
// half-planes meet exactly in the sector.
inline bool rightOfLeftEdge(const SonarCone& cone, double dx, double dy) {
  return dx * cone.left_edge.y() - dy * cone.left_edge.x() >= 0.0;
}
inline double radius2(double dx, double dy) {
  return dx * dx + dy * dy;
}

// For g monotone false -> true over [lo, hi]: the first index where g holds, hi + 1 if none.
// `guess` only decides where the walk starts; the answer is exact for any guess, and the walk is
// one or two steps when the guess comes from the analytic boundary.
template <class G>
int firstTrue(int lo, int hi, int guess, const G& g) {
  int c = std::clamp(guess, lo, hi + 1);
  if (c > lo && g(c - 1)) {
    --c;
    while (c > lo && g(c - 1))
      --c;
    return c;
  }
  while (c <= hi && !g(c))
    ++c;
  return c;
}

// For g monotone true -> false over [lo, hi]: the last index where g holds, lo - 1 if none.
template <class G>
int lastTrue(int lo, int hi, int guess, const G& g) {
  return firstTrue(lo, hi, guess + 1, [&g](int c) { return !g(c); }) - 1;
}

// A fractional column index (already floored or ceiled) as an int guess, clamped so that a huge,
// infinite or NaN estimate cannot overflow.
int toGuess(double index, int lo, int hi) {
  if (!(index > static_cast<double>(lo) - 1.0))
    return lo - 1;
  if (!(index < static_cast<double>(hi) + 1.0))
    return hi + 1;
  return static_cast<int>(index);
}

int clampedFloor(double v) {
  const double limit = static_cast<double>(OccupancyGrid::kMaxCellIndex) + 2.0;
  return static_cast<int>(std::clamp(std::floor(v), -limit, limit));
}

}  // namespace

ConeZone SonarCone::classify(double dx, double dy) const {
  if (!leftOfRightEdge(*this, dx, dy) || !rightOfLeftEdge(*this, dx, dy))
    return ConeZone::kOutside;
  const double r2 = radius2(dx, dy);
  if (r2 < free_radius2)
    return ConeZone::kFree;
  if (has_arc && r2 <= arc_outer_radius2)
    return ConeZone::kOccupied;
  return ConeZone::kOutside;
}

ConeZone SonarCone::classifyWithAngles(double dx, double dy) const {
  const double off_axis = wrapAngle(std::atan2(dy, dx) - heading_rad);
  if (std::abs(off_axis) > half_angle_rad)
    return ConeZone::kOutside;
  const double r = std::hypot(dx, dy);
  if (r < free_radius_m)
    return ConeZone::kFree;
  if (has_arc && r <= arc_outer_radius_m)
    return ConeZone::kOccupied;
  return ConeZone::kOutside;
}

ConeZone SonarCone::classifyCell(int col, int row, double resolution_m) const {
  return classify(cellCentreCoordinate(col, resolution_m) - apex.x(),
                  cellCentreCoordinate(row, resolution_m) - apex.y());
}

ConeZone SonarCone::classifyCellWithAngles(int col, int row, double resolution_m) const {
  return classifyWithAngles(cellCentreCoordinate(col, resolution_m) - apex.x(),
                            cellCentreCoordinate(row, resolution_m) - apex.y());
}

SonarCone makeSonarCone(const Vec2& origin, double heading_rad, double beam_width_rad,
                        double range_m, bool echo, const SonarInverseModel& model) {
  SonarCone cone;
  cone.apex = origin;
  cone.heading_rad = wrapAngle(heading_rad);
  cone.half_angle_rad = 0.5 * beam_width_rad;
  const double right = cone.heading_rad - cone.half_angle_rad;
  const double left = cone.heading_rad + cone.half_angle_rad;
  cone.right_edge = Vec2(std::cos(right), std::sin(right));
  cone.left_edge = Vec2(std::cos(left), std::sin(left));
  if (echo) {
    // Free in front of the arc band [range - arc/2, range + arc/2], occupied on it.
    const double half_arc = 0.5 * model.arc_thickness_m;
    cone.free_radius_m = std::max(0.0, range_m - half_arc);
    cone.has_arc = true;
    cone.arc_outer_radius_m = range_m + half_arc;
  } else {
    cone.free_radius_m = std::min(range_m, model.no_echo_free_range_m);
    cone.has_arc = false;
    cone.arc_outer_radius_m = cone.free_radius_m;
  }
  cone.free_radius2 = cone.free_radius_m * cone.free_radius_m;
  cone.arc_outer_radius2 = cone.arc_outer_radius_m * cone.arc_outer_radius_m;
  return cone;
}

OccupancyGrid::CellRect coneCellBounds(const SonarCone& cone, double resolution_m) {
  const double r = cone.outerRadius();
  Box2 box;
  box.extend(cone.apex);
  box.extend(Vec2(cone.apex + r * cone.right_edge));
  box.extend(Vec2(cone.apex + r * cone.left_edge));
  // The arc reaches further than its end points where it crosses an axis direction.
  const Vec2 axes[4] = {Vec2::UnitX(), Vec2::UnitY(), -Vec2::UnitX(), -Vec2::UnitY()};
  for (int k = 0; k < 4; ++k) {
    const double direction = wrapAngle(k * 0.5 * kPi);
    if (std::abs(wrapAngle(direction - cone.heading_rad)) <= cone.half_angle_rad)
      box.extend(Vec2(cone.apex + r * axes[k]));
  }
  // One cell of padding covers centres that pass the criterion by rounding alone.
  OccupancyGrid::CellRect rect;
  rect.col0 = clampedFloor(box.min.x() / resolution_m) - 1;
  rect.row0 = clampedFloor(box.min.y() / resolution_m) - 1;
  rect.col1 = clampedFloor(box.max.x() / resolution_m) + 1;
  rect.row1 = clampedFloor(box.max.y() / resolution_m) + 1;
  return rect;
}

void rasteriseCone(const SonarCone& cone, double resolution_m, std::vector<ConeSpan>& spans) {
  spans.clear();
  if (!cone.has_arc && !(cone.free_radius2 > 0.0))
    return;  // nothing can satisfy |d|^2 < 0
  const OccupancyGrid::CellRect bounds = coneCellBounds(cone, resolution_m);
  const double ox = cone.apex.x(), oy = cone.apex.y();
  const double res = resolution_m;
  const int lo = bounds.col0, hi = bounds.col1;
  // Fractional column index of world x: the centre of column c is at (c + 0.5) * res.
  const auto colOf = [res](double x) { return x / res - 0.5; };
  const int apex_col = toGuess(std::ceil(colOf(ox)), lo, hi);

  for (int row = bounds.row0; row <= bounds.row1; ++row) {
    const double dy = cellCentreCoordinate(row, res) - oy;
    const double dy2 = dy * dy;
    // |d|^2 >= dy^2 for every cell of the row (rounding is monotone), so whole rows drop out.
    if (cone.has_arc ? !(dy2 <= cone.arc_outer_radius2) : !(dy2 < cone.free_radius2))
      continue;
    const auto dxOf = [&](int col) { return cellCentreCoordinate(col, res) - ox; };

    // 1. The beam: each edge test is monotone along the row, its direction set by the sign of
    // the edge's y component. Estimates from the edge/row intersection x = ox + dy * ux / uy.
    int wa = lo, wb = hi;
    {
      const Vec2& u = cone.right_edge;
      const auto ok = [&](int col) { return leftOfRightEdge(cone, dxOf(col), dy); };
      if (u.y() > 0.0) {
        wb = lastTrue(lo, hi, toGuess(std::floor(colOf(ox + dy * u.x() / u.y())), lo, hi), ok);
      } else if (u.y() < 0.0) {
        wa = firstTrue(lo, hi, toGuess(std::ceil(colOf(ox + dy * u.x() / u.y())), lo, hi), ok);
      } else if (!ok(lo)) {
        continue;  // a horizontal edge: the row is entirely on one side
      }
    }
    {
      const Vec2& u = cone.left_edge;
      const auto ok = [&](int col) { return rightOfLeftEdge(cone, dxOf(col), dy); };
      if (u.y() > 0.0) {
        wa = std::max(
            wa, firstTrue(lo, hi, toGuess(std::ceil(colOf(ox + dy * u.x() / u.y())), lo, hi), ok));
      } else if (u.y() < 0.0) {
        wb = std::min(
            wb, lastTrue(lo, hi, toGuess(std::floor(colOf(ox + dy * u.x() / u.y())), lo, hi), ok));
      } else if (!ok(lo)) {
        continue;
      }
    }
    if (wa > wb)
      continue;

    // 2. The discs |d|^2 < r_free^2 and |d|^2 <= r_outer^2: along the row |d|^2 falls until the
    // column where dx turns non-negative and rises after it, so each disc is one interval found
    // by a search on either side of that column. Estimates: x = ox -+ sqrt(r^2 - dy^2).
    const int split = firstTrue(lo, hi, apex_col, [&](int col) { return dxOf(col) >= 0.0; });
    const auto discInterval = [&](double r2, bool strict, int& a, int& b) {
      const auto inside = [&](int col) {
        const double d2 = radius2(dxOf(col), dy);
        return strict ? d2 < r2 : d2 <= r2;
      };
      const double half_chord = std::sqrt(std::max(0.0, r2 - dy2));
      a = firstTrue(lo, split - 1, toGuess(std::ceil(colOf(ox - half_chord)), lo, hi), inside);
      b = lastTrue(split, hi, toGuess(std::floor(colOf(ox + half_chord)), lo, hi), inside);
    };
    int fa = 0, fb = -1;  // free cells
    if (dy2 < cone.free_radius2)
      discInterval(cone.free_radius2, true, fa, fb);

    const auto emit = [&](int a, int b, ConeZone zone) {
      a = std::max(a, wa);
      b = std::min(b, wb);
      if (a <= b)
        spans.push_back({row, a, b, zone});
    };
    if (cone.has_arc) {
      // The free disc lies inside the outer disc (r_free <= r_outer), so the arc band of the row
      // is the outer interval minus the free one: up to two runs.
      int oa = 0, ob = -1;
      discInterval(cone.arc_outer_radius2, false, oa, ob);
      if (fa > fb) {
        emit(oa, ob, ConeZone::kOccupied);
      } else {
        emit(oa, fa - 1, ConeZone::kOccupied);
        emit(fa, fb, ConeZone::kFree);
        emit(fb + 1, ob, ConeZone::kOccupied);
      }
    } else {
      emit(fa, fb, ConeZone::kFree);
    }
  }
}

}  // namespace irgs
