#include "core/mapping/sonar_cone.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

// This file is compiled with -ffp-contract=off (core/mapping/CMakeLists.txt): the rasteriser
// and classify() must round every expression identically, which a fused multiply-add in one
// place and not the other would break.

#if defined(__GNUC__)
#define IRGS_ALWAYS_INLINE __attribute__((always_inline))
#else
#define IRGS_ALWAYS_INLINE
#endif

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

// floor(x) clamped to [lo - 2, hi + 1] (callers treat anything below lo as "none"). Clears
// `decided` unless x is further than `margin` (< 0.5) from every integer (NaN never is): then a
// boundary estimated at x with an error under margin lies between the same two cell centres as the
// true one, and the criterion need not be evaluated. Branch free, and without an int round trip
// on the way to the decision: x, clamped to +-1.5 beyond the box (so that |x| < 2^51), is rounded
// to the nearest integer r by adding and subtracting 1.5 * 2^52, and x - r is exact.
inline int floorDecided(double x, int lo, int hi, double margin, bool& decided) {
  constexpr double kRound = 6755399441055744.0;  // 1.5 * 2^52
  const double lo_edge = static_cast<double>(lo) - 1.5;
  const double hi_edge = static_cast<double>(hi) + 1.5;
  double c = x > lo_edge ? x : lo_edge;  // NaN gives lo_edge...
  c = c < hi_edge ? c : hi_edge;
  const double r = (c + kRound) - kRound;
  const double d = c - r;                        // in [-0.5, 0.5]
  decided &= (std::abs(d) > margin) & (x == x);  // ...and is not decided
  return static_cast<int>(r) - static_cast<int>(d < 0.0);
}

#if defined(__SSE2__)
// floorDecided on two lanes: the same operations (max/min keep the scalar NaN behaviour: a NaN
// first operand yields the second), results k0 (lane 0) and k1 (lane 1). lo_edge and hi_edge are
// lo - 1.5 and hi + 1.5.
inline void floorDecided2(__m128d x, __m128d margin, __m128d lo_edge, __m128d hi_edge, int& k0,
                          int& k1, bool& decided) {
  const __m128d round = _mm_set1_pd(6755399441055744.0);  // 1.5 * 2^52
  const __m128d c = _mm_min_pd(_mm_max_pd(x, lo_edge), hi_edge);
  const __m128d r = _mm_sub_pd(_mm_add_pd(c, round), round);
  const __m128d d = _mm_sub_pd(c, r);
  const __m128d abs_d = _mm_andnot_pd(_mm_set1_pd(-0.0), d);
  const __m128d ok = _mm_and_pd(_mm_cmpgt_pd(abs_d, margin), _mm_cmpord_pd(x, x));
  decided &= _mm_movemask_pd(ok) == 3;
  const __m128d floored =
      _mm_sub_pd(r, _mm_and_pd(_mm_cmplt_pd(d, _mm_setzero_pd()), _mm_set1_pd(1.0)));
  const __m128i k = _mm_cvttpd_epi32(floored);
  k0 = _mm_cvtsi128_si32(k);
  k1 = _mm_cvtsi128_si32(_mm_shuffle_epi32(k, 1));
}
#endif

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

void scanConeRows(const SonarCone& cone, double resolution_m, std::vector<ConeRow>& rows) {
  scanConeRows(cone, resolution_m, rows, nullptr);
}

void scanConeRows(const SonarCone& cone, double resolution_m, std::vector<ConeRow>& rows,
                  ConeRowObserver* observer) {
  rows.clear();
  if (!cone.has_arc && !(cone.free_radius2 > 0.0))
    return;  // nothing can satisfy |d|^2 < 0
  const OccupancyGrid::CellRect bounds = coneCellBounds(cone, resolution_m);
  const double ox = cone.apex.x(), oy = cone.apex.y();
  const double res = resolution_m;
  const double inv_res = 1.0 / res;
  const int lo = bounds.col0, hi = bounds.col1;
  const auto dxOf = [&](int col) { return cellCentreCoordinate(col, res) - ox; };
  // Estimates only (the criterion decides): fractional column index of x = ox + dx, the centre
  // of column c being at (c + 0.5) * res.
  const double apex_col = ox * inv_res - 0.5;

  // Along a row |d|^2 falls while dx < 0 and rises from the first column with dx >= 0 (rounding
  // is monotone), so each disc is one interval, searched on either side of that column. dx does
  // not depend on the row: one search per cone.
  const int split =
      firstTrue(lo, hi, ceilGuess(apex_col, lo, hi), [&](int col) { return dxOf(col) >= 0.0; });

  // The two edge tests are monotone along a row, their direction set by the sign of the edge's y
  // component; the edge crosses the row at column apex_col + dy * ux / (uy * res).
  const Vec2& ur = cone.right_edge;
  const Vec2& ul = cone.left_edge;
  const double right_slope = ur.y() != 0.0 ? ur.x() / ur.y() * inv_res : 0.0;
  const double left_slope = ul.y() != 0.0 ? ul.x() / ul.y() * inv_res : 0.0;

  // Error bounds, in columns, of the boundary estimates against the criterion evaluated in
  // floating point (the criterion is exact real arithmetic on the same double inputs up to these
  // errors). With eps = 2^-52, M a bound on the magnitude of every coordinate involved (apex,
  // cell centres): a centre offset dx = (c + 0.5) * res - ox is off by <= eps M; the edge test
  // u x d by <= 4 eps M, i.e. 4 eps M / (|u_y| res) columns; the edge estimate by as much again.
  // A disc test |d|^2 < r^2 is off by <= 7 eps M R, i.e. <= 4 eps M R / (h res) columns where the
  // half chord is h metres; its estimate by <= 6 eps M R / (h res) + eps M / res. Each bound
  // below carries a further factor of 8. An estimate further than its bound from every cell
  // centre is the boundary itself (floorDecided); otherwise the criterion is evaluated there.
  const double big_m = std::abs(ox) + std::abs(oy) + cone.outerRadius() + 4.0 * res;
  // The last rounding of an estimate, |x| <= max(|lo|, |hi|) + 2 where it matters.
  const double position_err = 16.0 * kEps * (std::max(std::abs(lo), std::abs(hi)) + 4.0);
  const double right_err =
      ur.y() != 0.0 ? 64.0 * kEps * big_m / (std::abs(ur.y()) * res) + position_err : 0.0;
  const double left_err =
      ul.y() != 0.0 ? 64.0 * kEps * big_m / (std::abs(ul.y()) * res) + position_err : 0.0;
  const bool fast_edges = ur.y() != 0.0 && ul.y() != 0.0;
  const double disc_err =
      64.0 * kEps * big_m * inv_res * (cone.outerRadius() * inv_res + 1.0) + position_err;

#if defined(__SSE2__)
  const __m128d apex_v = _mm_set1_pd(apex_col);
  const __m128d slopes_v = _mm_set_pd(left_slope, right_slope);  // lanes: right, left
  const __m128d edge_err_v = _mm_set_pd(left_err, right_err);
  const __m128d disc_err_v = _mm_set1_pd(disc_err);
  const __m128d lo_v = _mm_set1_pd(static_cast<double>(lo) - 1.5);
  const __m128d hi_v = _mm_set1_pd(static_cast<double>(hi) + 1.5);
  const __m128d inv_res_v = _mm_set1_pd(inv_res);
  const __m128d ends_v = _mm_set_pd(1.0, -1.0);  // lanes: left end, right end
#endif

  // Rows outside the outer disc: |d|^2 >= dy^2 for every cell of the row.
  const double outer2 = cone.has_arc ? cone.arc_outer_radius2 : cone.free_radius2;
  const double free2 = cone.free_radius2;
  const bool outer_strict = !cone.has_arc;
#if defined(__SSE2__)
  const __m128d radii2_v = _mm_set_pd(free2, outer2);  // lanes: outer, free
#endif

  for (int row = bounds.row0; row <= bounds.row1; ++row) {
    const double dy = cellCentreCoordinate(row, res) - oy;
    const double dy2 = dy * dy;
    if (outer_strict ? !(dy2 < outer2) : !(dy2 <= outer2))
      continue;

    // 0. The usual case: every boundary estimate of the row is clear of cell centres. The six
    // estimates (two edges, two ends of each disc) are then the boundaries, each taken on the
    // whole box [lo, hi] and intersected afterwards, so that none waits for another.
    {
      bool decided = fast_edges;
      const bool free_row = cone.has_arc && dy2 < free2;
      bool free_decided = true;  // the free disc matters only on free rows
      int kr = 0, kl = 0, o0 = 0, o1 = 0, f0 = 0, f1 = 0;
#if defined(__SSE2__)
      // The same expressions as the scalar branch below, two lanes at a time.
      const __m128d dy_v = _mm_set1_pd(dy);
      floorDecided2(_mm_add_pd(apex_v, _mm_mul_pd(dy_v, slopes_v)), edge_err_v, lo_v, hi_v, kr, kl,
                    decided);
      const __m128d chords = _mm_mul_pd(
          _mm_sqrt_pd(_mm_max_pd(_mm_sub_pd(radii2_v, _mm_set1_pd(dy2)), _mm_setzero_pd())),
          inv_res_v);
      const double outer_chord = _mm_cvtsd_f64(chords);
      const double free_chord = _mm_cvtsd_f64(_mm_unpackhi_pd(chords, chords));
      floorDecided2(_mm_add_pd(apex_v, _mm_mul_pd(_mm_unpacklo_pd(chords, chords), ends_v)),
                    disc_err_v, lo_v, hi_v, o0, o1, decided);
      floorDecided2(_mm_add_pd(apex_v, _mm_mul_pd(_mm_unpackhi_pd(chords, chords), ends_v)),
                    disc_err_v, lo_v, hi_v, f0, f1, free_decided);
#else
      kr = floorDecided(apex_col + dy * right_slope, lo, hi, right_err, decided);
      kl = floorDecided(apex_col + dy * left_slope, lo, hi, left_err, decided);
      const double outer_chord = std::sqrt(std::max(0.0, outer2 - dy2)) * inv_res;
      o0 = floorDecided(apex_col + -1.0 * outer_chord, lo, hi, disc_err, decided);
      o1 = floorDecided(apex_col + 1.0 * outer_chord, lo, hi, disc_err, decided);
      const double free_chord = std::sqrt(std::max(0.0, free2 - dy2)) * inv_res;
      f0 = floorDecided(apex_col + -1.0 * free_chord, lo, hi, disc_err, free_decided);
      f1 = floorDecided(apex_col + 1.0 * free_chord, lo, hi, disc_err, free_decided);
#endif
      ++o0;  // first column inside: ceil of the left end, never an integer here
      ++f0;
      decided &= outer_chord >= 1.0 && (!free_row || (free_decided && free_chord >= 1.0));
      if (decided) [[likely]] {
        // Right edge: uy > 0 keeps columns <= its crossing, uy < 0 those >= it; the left edge
        // the other way round.
        // Clamped to the box like the searches below (an estimate may say hi + 1).
        const int wa = std::max(ur.y() > 0.0 ? lo : kr + 1, ul.y() > 0.0 ? kl + 1 : lo);
        const int wb = std::min({ur.y() > 0.0 ? kr : hi, ul.y() > 0.0 ? hi : kl, hi});
        ConeRow out;
        out.row = row;
        out.col0 = std::max(wa, o0);
        out.col1 = std::min(wb, o1);
        if (out.col0 > out.col1)
          continue;
        if (!cone.has_arc) {
          out.free0 = out.col0;
          out.free1 = out.col1;
        } else if (free_row) {
          out.free0 = std::max(out.col0, f0);
          out.free1 = std::min(out.col1, f1);
        } else {
          out.free0 = out.col0;
          out.free1 = out.col0 - 1;
        }
        rows.push_back(out);
        if (observer != nullptr)
          observer->rowFound(out);
        continue;
      }
    }

    // 1. The beam [wa, wb].
    int wa = lo, wb = hi;
    {
      const auto ok = [&](int col) { return leftOfRightEdge(cone, dxOf(col), dy); };
      const double at = apex_col + dy * right_slope;
      if (ur.y() > 0.0)
        wb = lastTrueNear(lo, hi, floorGuess(at, lo, hi), ok);
      else if (ur.y() < 0.0)
        wa = firstTrueNear(lo, hi, ceilGuess(at, lo, hi), ok);
      else if (!ok(lo))
        continue;  // a horizontal edge: the row is entirely on one side
    }
    {
      const auto ok = [&](int col) { return rightOfLeftEdge(cone, dxOf(col), dy); };
      const double at = apex_col + dy * left_slope;
      if (ul.y() > 0.0)
        wa = std::max(wa, firstTrueNear(lo, hi, ceilGuess(at, lo, hi), ok));
      else if (ul.y() < 0.0)
        wb = std::min(wb, lastTrueNear(lo, hi, floorGuess(at, lo, hi), ok));
      else if (!ok(lo))
        continue;
    }
    if (wa > wb)
      continue;

    // 2. A disc's cells within [a, b], an interval [first, last] (empty when first > last):
    // when an end of [a, b] is inside it is that end; otherwise left of the split the first
    // inside column, right of it the last one, each estimated at ox -+ sqrt(r^2 - dy^2). Rows
    // wholly inside (most rows of a cone seen side on) cost two evaluations and no root.
    // (Forced inline: as a call it cost GCC a tenth of a short cone's time.)
    const auto discInterval = [&](double r2, auto inside, int a, int b, int& first,
                                  int& last) IRGS_ALWAYS_INLINE {
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
      first = a_in            ? a
              : a <= left_end ? firstTrueNear(a, left_end,
                                              ceilGuess(apex_col - half_chord, a, left_end), inside)
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

    ConeRow out;
    out.row = row;
    if (outer_strict)
      discInterval(outer2, insideStrict(outer2), wa, wb, out.col0, out.col1);
    else
      discInterval(outer2, insideClosed(outer2), wa, wb, out.col0, out.col1);
    if (out.col0 > out.col1)
      continue;
    if (!cone.has_arc) {
      out.free0 = out.col0;
      out.free1 = out.col1;
    } else if (dy2 < free2) {
      // The free disc lies inside the outer one (r_free <= r_outer): search within the row's
      // cone cells only.
      discInterval(free2, insideStrict(free2), out.col0, out.col1, out.free0, out.free1);
    } else {
      out.free0 = out.col0;
      out.free1 = out.col0 - 1;
    }
    rows.push_back(out);
    if (observer != nullptr)
      observer->rowFound(out);
  }
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
