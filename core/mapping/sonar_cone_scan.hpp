#pragma once
// The row scan of a sonar cone (scanConeRows), split so that its common case is vectorised:
//
// 1. estimateConeRows: for every row of the cone's bounding box at once, the six analytic
//    boundary estimates (two edges, two ends of each disc), each taken as the boundary itself
//    when it is further from every cell centre than its error bound, else the row is marked
//    undecided. One straight loop of double arithmetic without branches, written here inline so
//    that the including file vectorises it across rows. It must be compiled with
//    -fno-math-errno and -fno-trapping-math, or GCC keeps the loop scalar (a square root that
//    might set errno, conditional arithmetic it may not speculate), and with -ffp-contract=off
//    like the criterion; core/mapping/CMakeLists.txt sets all three for the files that include
//    this. None changes a result: no code there reads errno or traps on exceptions.
// 2. scanConeRowExact: the rows left undecided (a boundary within rounding of a cell centre, a
//    chord shorter than a cell, a horizontal edge), by evaluating the criterion around each
//    estimate. Out of line (sonar_cone.cpp): rare.
//
// Either way a row's cells are exactly those SonarCone::classify() puts in the cone; the error
// bounds that make step 1 exact are derived in makeConeScanSetup.

#include <cmath>
#include <cstddef>
#include <vector>

#include "core/mapping/sonar_cone.hpp"

#if defined(__GNUC__)
#define IRGS_SCAN_INLINE inline __attribute__((always_inline))
#else
#define IRGS_SCAN_INLINE inline
#endif

namespace irgs {

// Per-cone constants of the scan (makeConeScanSetup).
struct ConeScanSetup {
  int row0 = 0, row1 = -1;  // the rows of the bounding box
  int lo = 0, hi = -1;      // its columns
  double oy = 0.0;          // apex y
  double res = 1.0, inv_res = 1.0;
  double apex_col = 0.0;  // fractional column of the apex (estimates only)
  double right_slope = 0.0, left_slope = 0.0;
  double right_err = 0.0, left_err = 0.0, disc_err = 0.0;  // error bounds, in columns
  double outer2 = 0.0, free2 = 0.0;
  bool has_cells = false;    // false: nothing can be in the cone (no rows at all)
  bool has_arc = false;      // free on the inner disc, occupied on the band around it
  bool outer_strict = true;  // the outer disc is |d|^2 < r^2 (no arc) or <= r^2 (arc)
  bool fast_edges = false;   // neither edge horizontal: step 1 can decide rows
  bool right_up = false;     // right edge's y > 0: it bounds columns from above
  bool left_up = false;      // left edge's y > 0: it bounds columns from below
  int split = 0;             // first column with dx >= 0 (the exact path's disc searches)
};

ConeScanSetup makeConeScanSetup(const SonarCone& cone, double resolution_m,
                                const OccupancyGrid::CellRect& bounds);

// The cone's cells in one row by the exact path; false when the row has none.
bool scanConeRowExact(const SonarCone& cone, const ConeScanSetup& setup, int row, ConeRow& out);

// The result of step 1, one entry per bounding-box row (index row - row0): cells [col0, col1]
// (none when col0 > col1), of which [free0, free1] are free (none when free0 > free1). Held as
// doubles (exact integers): the estimate loop then works on 64-bit lanes only, which GCC
// vectorises four rows to a 256-bit register without repacking (int outputs made it work on
// eight rows at a time and spill). col0 == kUndecidedRow: the row needs scanConeRowExact.
inline constexpr double kUndecidedRow = -0x1p40;  // no column is that far out
struct ConeRowEstimates {
  int count = 0;
  double* col0 = nullptr;
  double* col1 = nullptr;
  double* free0 = nullptr;
  double* free1 = nullptr;

  bool undecided(int i) const { return col0[i] == kUndecidedRow; }
  int c0(int i) const { return static_cast<int>(col0[i]); }
  int c1(int i) const { return static_cast<int>(col1[i]); }
  int f0(int i) const { return static_cast<int>(free0[i]); }
  int f1(int i) const { return static_cast<int>(free1[i]); }
  void set(int i, int first, int last, int first_free, int last_free) {
    col0[i] = first;
    col1[i] = last;
    free0[i] = first_free;
    free1[i] = last_free;
  }

  // Views `rows` rows of `storage` with room for `capacity` >= rows per array, grown when needed
  // (kept by the caller between cones, so that a warm scan allocates nothing).
  void bind(std::vector<double>& storage, int rows, int capacity) {
    count = rows;
    const auto n = static_cast<std::size_t>(capacity);
    if (storage.size() < 4 * n)
      storage.resize(4 * n);
    col0 = storage.data();
    col1 = col0 + n;
    free0 = col1 + n;
    free1 = free0 + n;
  }
};

namespace cone_scan_detail {

// floor(x) (as a double) when x is further than `margin` (< 0.5) from every integer: then a
// boundary estimated at x with an error under margin lies between the same two cell centres as
// the true one, and the criterion need not be evaluated; otherwise (NaN included) clears
// `decided`. x is first clamped to 1.5 beyond the box (so that |x| < 2^51, and the result fits an
// int), then rounded to the nearest integer r by adding and subtracting 1.5 * 2^52; x - r is
// exact. Branch free: the ternaries are max/min instructions.
inline double floorDecided(double x, double lo_edge, double hi_edge, double margin, bool& decided) {
  constexpr double kRound = 6755399441055744.0;  // 1.5 * 2^52
  double c = x > lo_edge ? x : lo_edge;          // NaN gives lo_edge...
  c = c < hi_edge ? c : hi_edge;
  const double r = (c + kRound) - kRound;
  const double d = c - r;                                  // in [-0.5, 0.5]
  decided = decided & (std::fabs(d) > margin) & (x == x);  // ...and is not decided
  return d < 0.0 ? r - 1.0 : r;
}

// floorDecided without the clamp and the NaN test, for the disc ends (4 of the 6 estimates a
// row): x = apex column -+ a chord is always finite and within 2^31 of zero (the addressable
// check keeps |apex| under kMaxCellIndex columns, the chord is at most kMaxConeRadiusCells), so
// the rounding is exact without them. A disc end beyond the box then gives a column further
// out than the clamped one did; the caller's max / min with the beam interval (wa >= lo - 1,
// wb <= hi) gives the same row whenever the row has cells, and an empty one (c0 > c1, free0 >
// free1) where it had none. Only `decided` can differ, sending such a row to the exact path.
inline double floorDecidedDisc(double x, double margin, bool& decided) {
  constexpr double kRound = 6755399441055744.0;  // 1.5 * 2^52
  const double r = (x + kRound) - kRound;
  const double d = x - r;  // in [-0.5, 0.5]
  decided = decided & (std::fabs(d) > margin);
  return d < 0.0 ? r - 1.0 : r;
}

inline double maxd(double a, double b) {
  return a > b ? a : b;
}
inline double mind(double a, double b) {
  return a < b ? a : b;
}

// Step 1 for one combination of the cone's loop-invariant choices, so that the loop body has no
// branch. All column arithmetic is on doubles (exact on integers this size) until the store.
template <bool kRightUp, bool kLeftUp, bool kArc>
IRGS_SCAN_INLINE void estimateRows(const ConeScanSetup& s, int n, double* __restrict col0_out,
                                   double* __restrict col1_out, double* __restrict free0_out,
                                   double* __restrict free1_out) {
  const double lo = s.lo, hi = s.hi;
  const double lo_edge = lo - 1.5, hi_edge = hi + 1.5;
  const double row0 = s.row0;
  const double res = s.res, inv_res = s.inv_res, oy = s.oy, apex = s.apex_col;
  const double right_slope = s.right_slope, left_slope = s.left_slope;
  const double right_err = s.right_err, left_err = s.left_err, disc_err = s.disc_err;
  const double outer2 = s.outer2, free2 = s.free2;
  // First the rows' dy, into free1_out (overwritten below): with the int row index converted in
  // the main loop, GCC sized that loop's step by the int lanes (four rows with SSE2's two-double
  // registers, twice the live values); now it works on doubles only. 0.5 m cones: 2-4 % faster
  // on the AVX2 and AVX-512 paths, SSE2 unchanged (irgs_bench_mrpt_grid, 2026-12-04).
  for (int i = 0; i < n; ++i)  // cellCentreCoordinate(row0 + i, res) - oy, rounded the same way.
    free1_out[i] = (row0 + static_cast<double>(i) + 0.5) * res - oy;
  for (int i = 0; i < n; ++i) {
    const double dy = free1_out[i];
    const double dy2 = dy * dy;
    // Rows outside the outer disc are empty: |d|^2 >= dy^2 for every cell of the row.
    const bool in_outer = kArc ? dy2 <= outer2 : dy2 < outer2;
    bool decided = true;
    // The edges cross the row at column apex + dy * ux / (uy * res).
    const double kr = floorDecided(apex + dy * right_slope, lo_edge, hi_edge, right_err, decided);
    const double kl = floorDecided(apex + dy * left_slope, lo_edge, hi_edge, left_err, decided);
    const double outer_chord = std::sqrt(maxd(outer2 - dy2, 0.0)) * inv_res;
    // First column inside: ceil of the left end, never an integer here.
    const double o0 = floorDecidedDisc(apex - outer_chord, disc_err, decided) + 1.0;
    const double o1 = floorDecidedDisc(apex + outer_chord, disc_err, decided);
    decided = decided & (outer_chord >= 1.0);
    // Right edge: uy > 0 keeps columns <= its crossing, uy < 0 those >= it; the left edge the
    // other way round. Clamped to the box (an estimate may say hi + 1).
    const double wa = maxd(kRightUp ? lo : kr + 1.0, kLeftUp ? kl + 1.0 : lo);
    const double wb = mind(mind(kRightUp ? kr : hi, kLeftUp ? hi : kl), hi);
    const double c0 = maxd(wa, o0);
    const double c1 = mind(wb, o1);
    double fr0 = c0, fr1 = c1;  // no arc: every cell is free
    if constexpr (kArc) {
      // Free only on rows that meet the free disc (strictly inside it).
      const bool free_row = dy2 < free2;
      bool free_decided = true;
      const double free_chord = std::sqrt(maxd(free2 - dy2, 0.0)) * inv_res;
      const double f0 = floorDecidedDisc(apex - free_chord, disc_err, free_decided) + 1.0;
      const double f1 = floorDecidedDisc(apex + free_chord, disc_err, free_decided);
      decided = decided & ((!free_row) | (free_decided & (free_chord >= 1.0)));
      fr0 = free_row ? maxd(c0, f0) : c0;
      fr1 = free_row ? mind(c1, f1) : c0 - 1.0;
    }
    col0_out[i] = !in_outer ? lo : decided ? c0 : kUndecidedRow;
    col1_out[i] = !in_outer ? lo - 1.0 : c1;
    free0_out[i] = fr0;
    free1_out[i] = fr1;
  }
}

}  // namespace cone_scan_detail

// Step 1 over the setup's bounding-box rows, into `out` bound to `storage`. With fast_edges false
// every row is undecided. Forced inline so that estimateConeRowsAvx2 compiles the same loop for
// AVX2. kRowsPerStep: the rows one vector step of the caller's target computes (a power of two).
template <int kRowsPerStep = 4>
IRGS_SCAN_INLINE void estimateConeRows(const ConeScanSetup& s, std::vector<double>& storage,
                                       ConeRowEstimates& out) {
  using namespace cone_scan_detail;
  const int rows = s.has_cells ? s.row1 - s.row0 + 1 : 0;
  // The loop runs over a multiple of kRowsPerStep rows (the extra ones are computed, never
  // read): GCC then emits no scalar epilogue, which cost as much per row as a whole step of the
  // vector body (a quarter of the loop's time on 0.5 m cones).
  const int n = (rows + kRowsPerStep - 1) & ~(kRowsPerStep - 1);
  out.bind(storage, rows, n);
  if (!s.fast_edges) {
    for (int i = 0; i < rows; ++i)
      out.col0[i] = kUndecidedRow;
    return;
  }
  const int which = (s.right_up ? 4 : 0) | (s.left_up ? 2 : 0) | (s.has_arc ? 1 : 0);
  double* const c0 = out.col0;
  double* const c1 = out.col1;
  double* const f0 = out.free0;
  double* const f1 = out.free1;
  switch (which) {
    case 0:
      estimateRows<false, false, false>(s, n, c0, c1, f0, f1);
      break;
    case 1:
      estimateRows<false, false, true>(s, n, c0, c1, f0, f1);
      break;
    case 2:
      estimateRows<false, true, false>(s, n, c0, c1, f0, f1);
      break;
    case 3:
      estimateRows<false, true, true>(s, n, c0, c1, f0, f1);
      break;
    case 4:
      estimateRows<true, false, false>(s, n, c0, c1, f0, f1);
      break;
    case 5:
      estimateRows<true, false, true>(s, n, c0, c1, f0, f1);
      break;
    case 6:
      estimateRows<true, true, false>(s, n, c0, c1, f0, f1);
      break;
    default:
      estimateRows<true, true, true>(s, n, c0, c1, f0, f1);
      break;
  }
}

// estimateConeRows vectorised for AVX2 (sonar_cone.cpp): the same operations on four rows at a
// time, so the same results. Call only where gridSimdSupported says so.
void estimateConeRowsAvx2(const ConeScanSetup& s, std::vector<double>& storage,
                          ConeRowEstimates& out);
// The same with AVX-512 registers (still four rows at a time).
void estimateConeRowsAvx512(const ConeScanSetup& s, std::vector<double>& storage,
                            ConeRowEstimates& out);
inline void estimateConeRows(const ConeScanSetup& s, std::vector<double>& storage,
                             ConeRowEstimates& out, GridSimd simd) {
  if (simd == GridSimd::kAvx512)
    estimateConeRowsAvx512(s, storage, out);
  else if (simd == GridSimd::kAvx2)
    estimateConeRowsAvx2(s, storage, out);
  else
    estimateConeRows<>(s, storage, out);
}

// Row `row0 + i` of `est` as a ConeRow, running the exact path when step 1 left it undecided;
// false when the row has no cell.
inline bool coneRowAt(const SonarCone& cone, const ConeScanSetup& s, const ConeRowEstimates& est,
                      int i, ConeRow& out) {
  if (est.undecided(i)) [[unlikely]]
    return scanConeRowExact(cone, s, s.row0 + i, out);
  out.row = s.row0 + i;
  out.col0 = est.c0(i);
  out.col1 = est.c1(i);
  out.free0 = est.f0(i);
  out.free1 = est.f1(i);
  return out.col0 <= out.col1;
}

}  // namespace irgs
