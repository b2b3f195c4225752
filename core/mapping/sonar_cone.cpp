#include "core/mapping/sonar_cone.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/mapping/sonar_cone_scan.hpp"

// This file is compiled with -ffp-contract=off (core/mapping/CMakeLists.txt): the rasteriser
// and classify() must round every expression identically, which a fused multiply-add in one
// place and not the other would break. The common case of the row scan is in
// sonar_cone_scan.hpp (vectorised across rows); this file holds the exact per-row path.

namespace irgs {
namespace {

// The three tests of the criterion, written once and used by classify() and the rasteriser.
// In the beam: cross(u_r, d) >= 0 (d is counter-clockwise of the right edge)...
constexpr double kEps = std::numeric_limits<double>::epsilon();

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

// floor(x) as an index guess, clamped to [lo - 1, hi + 1] (NaN gives lo - 1), so that a huge,
// infinite or NaN estimate cannot overflow. Cheaper than std::floor plus a conversion: once
// clamped, x - (lo - 1) >= 0, where truncation is flooring. Rounding in that subtraction can
// only move a guess by one, which the callers' confirmation absorbs.
inline int floorGuess(double x, int lo, int hi) {
  const double t = x - (static_cast<double>(lo) - 1.0);
  if (!(t > 0.0))
    return lo - 1;
  if (!(t < static_cast<double>(hi - lo) + 2.0))
    return hi + 1;
  return lo - 1 + static_cast<int>(t);
}
// ceil(x) likewise.
inline int ceilGuess(double x, int lo, int hi) {
  return -floorGuess(-x, -hi, -lo);
}

// firstTrue for a guess that is almost always the answer (an analytic boundary estimate): two
// evaluations confirm it, without data-dependent branches in the common case; otherwise walks.
// Requires lo <= hi + 1.
template <class G>
inline int firstTrueNear(int lo, int hi, int guess, const G& g) {
  const int c = std::clamp(guess, lo, hi + 1);
  const bool below = c > lo && g(c - 1);  // the answer is left of c
  const bool above = c <= hi && !g(c);    // the answer is right of c
  if (!(below || above)) [[likely]]
    return c;
  return firstTrue(lo, hi, c, g);
}
template <class G>
inline int lastTrueNear(int lo, int hi, int guess, const G& g) {
  return firstTrueNear(lo, hi, guess + 1, [&g](int c) { return !g(c); }) - 1;
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
  // wrapAngle returns an angle already in (-pi, pi] unchanged (std::remainder is exact and
  // rounds the quotient 1/2 of pi to even, 0); tested first because std::remainder costs as
  // much as a sincos and headings usually come wrapped.
  cone.heading_rad =
      heading_rad > -kPi && heading_rad <= kPi ? heading_rad : wrapAngle(heading_rad);
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
  // The beam test is the criterion's own half-plane pair (a beam under pi is exactly their
  // intersection), so no angle arithmetic per call.
  const Vec2 axes[4] = {Vec2::UnitX(), Vec2::UnitY(), -Vec2::UnitX(), -Vec2::UnitY()};
  for (const Vec2& axis : axes) {
    if (leftOfRightEdge(cone, axis.x(), axis.y()) && rightOfLeftEdge(cone, axis.x(), axis.y()))
      box.extend(Vec2(cone.apex + r * axis));
  }
  // One cell of padding covers centres that pass the criterion by rounding alone.
  OccupancyGrid::CellRect rect;
  rect.col0 = clampedFloor(box.min.x() / resolution_m) - 1;
  rect.row0 = clampedFloor(box.min.y() / resolution_m) - 1;
  rect.col1 = clampedFloor(box.max.x() / resolution_m) + 1;
  rect.row1 = clampedFloor(box.max.y() / resolution_m) + 1;
  return rect;
}

ConeScanSetup makeConeScanSetup(const SonarCone& cone, double resolution_m,
                                const OccupancyGrid::CellRect& bounds) {
  ConeScanSetup s;
  s.has_cells = cone.has_arc || cone.free_radius2 > 0.0;  // nothing satisfies |d|^2 < 0
  s.row0 = bounds.row0;
  s.row1 = bounds.row1;
  s.lo = bounds.col0;
  s.hi = bounds.col1;
  const double ox = cone.apex.x();
  s.oy = cone.apex.y();
  s.res = resolution_m;
  s.inv_res = 1.0 / resolution_m;
  // Estimates only (the criterion decides): fractional column index of x = ox + dx, the centre
  // of column c being at (c + 0.5) * res.
  s.apex_col = ox * s.inv_res - 0.5;

  // Along a row |d|^2 falls while dx < 0 and rises from the first column with dx >= 0 (rounding
  // is monotone), so each disc is one interval, searched on either side of that column. dx does
  // not depend on the row: one search per cone.
  const int lo = s.lo, hi = s.hi;
  s.split = firstTrue(lo, hi, ceilGuess(s.apex_col, lo, hi),
                      [&](int col) { return cellCentreCoordinate(col, resolution_m) - ox >= 0.0; });

  // The two edge tests are monotone along a row, their direction set by the sign of the edge's y
  // component; the edge crosses the row at column apex_col + dy * ux / (uy * res).
  const Vec2& ur = cone.right_edge;
  const Vec2& ul = cone.left_edge;
  s.right_slope = ur.y() != 0.0 ? ur.x() / ur.y() * s.inv_res : 0.0;
  s.left_slope = ul.y() != 0.0 ? ul.x() / ul.y() * s.inv_res : 0.0;
  s.right_up = ur.y() > 0.0;
  s.left_up = ul.y() > 0.0;
  s.fast_edges = ur.y() != 0.0 && ul.y() != 0.0;

  // Error bounds, in columns, of the boundary estimates against the criterion evaluated in
  // floating point (the criterion is exact real arithmetic on the same double inputs up to these
  // errors). With eps = 2^-52, M a bound on the magnitude of every coordinate involved (apex,
  // cell centres): a centre offset dx = (c + 0.5) * res - ox is off by <= eps M; the edge test
  // u x d by <= 4 eps M, i.e. 4 eps M / (|u_y| res) columns; the edge estimate by as much again.
  // A disc test |d|^2 < r^2 is off by <= 7 eps M R, i.e. <= 4 eps M R / (h res) columns where the
  // half chord is h metres; its estimate by <= 6 eps M R / (h res) + eps M / res. Each bound
  // below carries a further factor of 8. An estimate further than its bound from every cell
  // centre is the boundary itself (estimateConeRows); otherwise the criterion is evaluated there.
  const double res = resolution_m;
  const double big_m = std::abs(ox) + std::abs(s.oy) + cone.outerRadius() + 4.0 * res;
  // The last rounding of an estimate, |x| <= max(|lo|, |hi|) + 2 where it matters.
  const double position_err = 16.0 * kEps * (std::max(std::abs(lo), std::abs(hi)) + 4.0);
  s.right_err = ur.y() != 0.0 ? 64.0 * kEps * big_m / (std::abs(ur.y()) * res) + position_err : 0.0;
  s.left_err = ul.y() != 0.0 ? 64.0 * kEps * big_m / (std::abs(ul.y()) * res) + position_err : 0.0;
  s.disc_err =
      64.0 * kEps * big_m * s.inv_res * (cone.outerRadius() * s.inv_res + 1.0) + position_err;

  s.has_arc = cone.has_arc;
  s.outer_strict = !cone.has_arc;
  s.outer2 = cone.has_arc ? cone.arc_outer_radius2 : cone.free_radius2;
  s.free2 = cone.free_radius2;
  return s;
}

bool scanConeRowExact(const SonarCone& cone, const ConeScanSetup& s, int row, ConeRow& out) {
  const double ox = cone.apex.x();
  const double res = s.res;
  const double inv_res = s.inv_res;
  const double apex_col = s.apex_col;
  const int lo = s.lo, hi = s.hi, split = s.split;
  const auto dxOf = [&](int col) { return cellCentreCoordinate(col, res) - ox; };
  const double dy = cellCentreCoordinate(row, res) - s.oy;
  const double dy2 = dy * dy;
  if (s.outer_strict ? !(dy2 < s.outer2) : !(dy2 <= s.outer2))
    return false;  // outside the outer disc: |d|^2 >= dy^2 for every cell of the row

  // 1. The beam [wa, wb].
  const Vec2& ur = cone.right_edge;
  const Vec2& ul = cone.left_edge;
  int wa = lo, wb = hi;
  {
    const auto ok = [&](int col) { return leftOfRightEdge(cone, dxOf(col), dy); };
    const double at = apex_col + dy * s.right_slope;
    if (ur.y() > 0.0)
      wb = lastTrueNear(lo, hi, floorGuess(at, lo, hi), ok);
    else if (ur.y() < 0.0)
      wa = firstTrueNear(lo, hi, ceilGuess(at, lo, hi), ok);
    else if (!ok(lo))
      return false;  // a horizontal edge: the row is entirely on one side
  }
  {
    const auto ok = [&](int col) { return rightOfLeftEdge(cone, dxOf(col), dy); };
    const double at = apex_col + dy * s.left_slope;
    if (ul.y() > 0.0)
      wa = std::max(wa, firstTrueNear(lo, hi, ceilGuess(at, lo, hi), ok));
    else if (ul.y() < 0.0)
      wb = std::min(wb, lastTrueNear(lo, hi, floorGuess(at, lo, hi), ok));
    else if (!ok(lo))
      return false;
  }
  if (wa > wb)
    return false;

  // 2. A disc's cells within [a, b], an interval [first, last] (empty when first > last):
  // when an end of [a, b] is inside it is that end; otherwise left of the split the first
  // inside column, right of it the last one, each estimated at ox -+ sqrt(r^2 - dy^2). Rows
  // wholly inside (most rows of a cone seen side on) cost two evaluations and no root.
  const auto discInterval = [&](double r2, auto inside, int a, int b, int& first, int& last) {
    const bool a_in = inside(a);
    const bool b_in = inside(b);
    if (a_in && b_in) {
      first = a;
      last = b;
      return;
    }
    const double half_chord = std::sqrt(std::max(0.0, r2 - dy2)) * inv_res;
    const int left_end = std::min(b, split - 1);
    const int right_start = std::max(a, split);
    first = a_in ? a
            : a <= left_end
                ? firstTrueNear(a, left_end, ceilGuess(apex_col - half_chord, a, left_end), inside)
                : right_start;
    last = b_in ? b
           : right_start <= b
               ? lastTrueNear(right_start, b, floorGuess(apex_col + half_chord, right_start, b),
                              inside)
               : left_end;
  };
  const auto insideStrict = [&](double r2) {
    return [&dxOf, dy2, r2](int col) {
      const double dx = dxOf(col);
      return dx * dx + dy2 < r2;  // radius2(dx, dy), the same rounding
    };
  };
  const auto insideClosed = [&](double r2) {
    return [&dxOf, dy2, r2](int col) {
      const double dx = dxOf(col);
      return dx * dx + dy2 <= r2;
    };
  };

  out.row = row;
  if (s.outer_strict)
    discInterval(s.outer2, insideStrict(s.outer2), wa, wb, out.col0, out.col1);
  else
    discInterval(s.outer2, insideClosed(s.outer2), wa, wb, out.col0, out.col1);
  if (out.col0 > out.col1)
    return false;
  if (!s.has_arc) {
    out.free0 = out.col0;
    out.free1 = out.col1;
  } else if (dy2 < s.free2) {
    // The free disc lies inside the outer one (r_free <= r_outer): search within the row's
    // cone cells only.
    discInterval(s.free2, insideStrict(s.free2), out.col0, out.col1, out.free0, out.free1);
  } else {
    out.free0 = out.col0;
    out.free1 = out.col0 - 1;
  }
  return true;
}

#if defined(__x86_64__) && defined(__GNUC__)
__attribute__((target("avx2"))) void estimateConeRowsAvx2(const ConeScanSetup& s,
                                                          std::vector<double>& storage,
                                                          ConeRowEstimates& out) {
  estimateConeRows(s, storage, out);
}
// 512-bit vectors, eight rows a step, with AVX-512's 32 vector registers (the loop's ~30
// constants stay in registers). On AMD Zen 4 (a 512-bit operation issued as two 256-bit halves)
// still faster than four rows a step (prefer-vector-width=256, the previous setting): half the
// instructions, 0.05-0.06 us less a 0.5 m cone, 3-6 % less a 1.5 or 3 m cone.
__attribute__((target("avx512f,avx512vl,avx512bw,avx512dq,prefer-vector-width=512"))) void
estimateConeRowsAvx512(const ConeScanSetup& s, std::vector<double>& storage,
                       ConeRowEstimates& out) {
  estimateConeRows<8>(s, storage, out);
}
#else
// Never called: gridSimdSupported is false for AVX2 and AVX-512 here.
void estimateConeRowsAvx512(const ConeScanSetup& s, std::vector<double>& storage,
                            ConeRowEstimates& out) {
  estimateConeRows(s, storage, out);
}
void estimateConeRowsAvx2(const ConeScanSetup& s, std::vector<double>& storage,
                          ConeRowEstimates& out) {
  estimateConeRows(s, storage, out);
}
#endif

void scanConeRows(const SonarCone& cone, double resolution_m, std::vector<ConeRow>& rows,
                  GridSimd simd) {
  if (!gridSimdSupported(simd))
    throw std::invalid_argument("scanConeRows: instruction set not supported here");
  rows.clear();
  const ConeScanSetup setup =
      makeConeScanSetup(cone, resolution_m, coneCellBounds(cone, resolution_m));
  std::vector<double> storage;
  ConeRowEstimates estimates;
  estimateConeRows(setup, storage, estimates, simd);
  ConeRow row;
  for (int i = 0; i < estimates.count; ++i)
    if (coneRowAt(cone, setup, estimates, i, row))
      rows.push_back(row);
}

void scanConeRowsExact(const SonarCone& cone, double resolution_m, std::vector<ConeRow>& rows) {
  rows.clear();
  const ConeScanSetup setup =
      makeConeScanSetup(cone, resolution_m, coneCellBounds(cone, resolution_m));
  if (!setup.has_cells)
    return;
  ConeRow row;
  for (int r = setup.row0; r <= setup.row1; ++r)
    if (scanConeRowExact(cone, setup, r, row))
      rows.push_back(row);
}

void rasteriseCone(const SonarCone& cone, double resolution_m, std::vector<ConeSpan>& spans) {
  spans.clear();
  std::vector<ConeRow> rows;
  scanConeRows(cone, resolution_m, rows);
  for (const ConeRow& r : rows) {
    if (!r.hasFree()) {
      spans.push_back({r.row, r.col0, r.col1, ConeZone::kOccupied});
      continue;
    }
    if (r.col0 < r.free0)
      spans.push_back({r.row, r.col0, r.free0 - 1, ConeZone::kOccupied});
    spans.push_back({r.row, r.free0, r.free1, ConeZone::kFree});
    if (r.free1 < r.col1)
      spans.push_back({r.row, r.free1 + 1, r.col1, ConeZone::kOccupied});
  }
}

}  // namespace irgs
