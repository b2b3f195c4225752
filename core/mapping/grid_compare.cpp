#include "core/mapping/grid_compare.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace irgs {
namespace {

enum : std::uint8_t { kUnknown = 0, kFree = 1, kOccupied = 2 };

// Lattice index of grid cell `index` (cell size `res`) on a lattice of cell size `lattice`:
// the lattice cell holding the grid cell's centre. Equal sizes map a cell to itself exactly.
std::int64_t latticeIndex(int index, double res, double lattice) {
  if (res == lattice)
    return index;
  return static_cast<std::int64_t>(std::floor((static_cast<double>(index) + 0.5) * res / lattice));
}

struct LatticeRect {
  std::int64_t col0 = 0, row0 = 0, col1 = -1, row1 = -1;
  bool empty() const { return col1 < col0 || row1 < row0; }
};

LatticeRect latticeRect(const OccupancyGrid& grid, double lattice) {
  const OccupancyGrid::CellRect r = grid.observedCellRect();
  if (r.empty())
    return {};
  const double res = grid.resolution_m();
  return {latticeIndex(r.col0, res, lattice), latticeIndex(r.row0, res, lattice),
          latticeIndex(r.col1, res, lattice), latticeIndex(r.row1, res, lattice)};
}

// The grid's classes on the lattice window `window` (row-major, width w).
std::vector<std::uint8_t> classify(const OccupancyGrid& grid, double lattice,
                                   const LatticeRect& window, const GridCompareOptions& options) {
  const std::int64_t w = window.col1 - window.col0 + 1;
  const std::int64_t h = window.row1 - window.row0 + 1;
  std::vector<std::uint8_t> classes(static_cast<std::size_t>(w * h), kUnknown);
  const OccupancyGrid::CellRect r = grid.observedCellRect();
  if (r.empty())
    return classes;
  std::vector<float> log_odds;
  grid.copyLogOdds(r, log_odds);
  const double res = grid.resolution_m();
  std::vector<std::int64_t> lattice_cols(static_cast<std::size_t>(r.width()));
  for (int c = 0; c < r.width(); ++c)
    lattice_cols[static_cast<std::size_t>(c)] =
        latticeIndex(r.col0 + c, res, lattice) - window.col0;
  for (int row = 0; row < r.height(); ++row) {
    const std::int64_t lr = latticeIndex(r.row0 + row, res, lattice) - window.row0;
    const float* values = log_odds.data() + static_cast<std::size_t>(row) * r.width();
    for (int c = 0; c < r.width(); ++c) {
      const float v = values[c];
      if (std::isnan(v))
        continue;
      const std::uint8_t cls = v > options.occupied_log_odds ? kOccupied
                               : v < options.free_log_odds   ? kFree
                                                             : kUnknown;
      std::uint8_t& cell = classes[static_cast<std::size_t>(lr * w + lattice_cols[c])];
      cell = std::max(cell, cls);
    }
  }
  return classes;
}

OccupiedAgreement agreementOf(std::size_t matched_candidate, std::size_t candidate,
                              std::size_t matched_reference, std::size_t reference) {
  OccupiedAgreement a;
  if (candidate == 0 && reference == 0) {
    a.precision = a.recall = a.f1 = 1.0;
    return a;
  }
  a.precision =
      candidate > 0 ? static_cast<double>(matched_candidate) / static_cast<double>(candidate) : 0.0;
  a.recall =
      reference > 0 ? static_cast<double>(matched_reference) / static_cast<double>(reference) : 0.0;
  a.f1 =
      a.precision + a.recall > 0.0 ? 2.0 * a.precision * a.recall / (a.precision + a.recall) : 0.0;
  return a;
}

// Occupied cells of `from` with an occupied cell of `to` within `tolerance` (Chebyshev).
std::size_t matchedWithin(const std::vector<std::uint8_t>& from,
                          const std::vector<std::uint8_t>& to, std::int64_t w, std::int64_t h,
                          int tolerance) {
  std::size_t matched = 0;
  for (std::int64_t row = 0; row < h; ++row) {
    for (std::int64_t col = 0; col < w; ++col) {
      if (from[static_cast<std::size_t>(row * w + col)] != kOccupied)
        continue;
      bool found = false;
      for (std::int64_t r = std::max<std::int64_t>(0, row - tolerance);
           !found && r <= std::min(h - 1, row + tolerance); ++r) {
        for (std::int64_t c = std::max<std::int64_t>(0, col - tolerance);
             c <= std::min(w - 1, col + tolerance); ++c) {
          if (to[static_cast<std::size_t>(r * w + c)] == kOccupied) {
            found = true;
            break;
          }
        }
      }
      matched += found ? 1 : 0;
    }
  }
  return matched;
}

}  // namespace

std::optional<std::string> gridCompareOptionsError(const GridCompareOptions& options) {
  if (!std::isfinite(options.occupied_log_odds) || !std::isfinite(options.free_log_odds))
    return "grid comparison thresholds must be finite";
  if (options.free_log_odds > options.occupied_log_odds)
    return "grid comparison: the free threshold is above the occupied one";
  if (!std::isfinite(options.resolution_m) || options.resolution_m < 0.0)
    return "grid comparison: the lattice resolution must be >= 0";
  if (options.tolerance_cells < 0)
    return "grid comparison: the tolerance must be >= 0 cells";
  return std::nullopt;
}

GridComparison compareGrids(const OccupancyGrid& reference, const OccupancyGrid& candidate,
                            const GridCompareOptions& options) {
  if (const auto error = gridCompareOptionsError(options))
    throw std::invalid_argument(*error);
  const double coarser = std::max(reference.resolution_m(), candidate.resolution_m());
  const double lattice = options.resolution_m > 0.0 ? options.resolution_m : coarser;
  if (lattice < coarser)
    throw std::invalid_argument("grid comparison: the lattice is finer than a grid");

  GridComparison out;
  out.resolution_m = lattice;
  out.identical = reference == candidate;
  LatticeRect window = latticeRect(reference, lattice);
  const LatticeRect other = latticeRect(candidate, lattice);
  if (window.empty()) {
    window = other;
  } else if (!other.empty()) {
    window.col0 = std::min(window.col0, other.col0);
    window.row0 = std::min(window.row0, other.row0);
    window.col1 = std::max(window.col1, other.col1);
    window.row1 = std::max(window.row1, other.row1);
  }
  if (window.empty()) {
    out.occupied = out.occupied_tolerant = agreementOf(0, 0, 0, 0);
    return out;
  }
  const std::int64_t w = window.col1 - window.col0 + 1;
  const std::int64_t h = window.row1 - window.row0 + 1;
  if (w > kMaxCompareCells / h)
    throw std::invalid_argument("grid comparison: the observed areas are too large");

  const std::vector<std::uint8_t> a = classify(reference, lattice, window, options);
  const std::vector<std::uint8_t> b = classify(candidate, lattice, window, options);
  std::size_t both_occupied = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a[i] == kUnknown && b[i] == kUnknown)
      continue;
    ++out.compared_cells;
    out.same_class_cells += a[i] == b[i] ? 1 : 0;
    out.reference_only += b[i] == kUnknown ? 1 : 0;
    out.candidate_only += a[i] == kUnknown ? 1 : 0;
    out.reference_occupied += a[i] == kOccupied ? 1 : 0;
    out.candidate_occupied += b[i] == kOccupied ? 1 : 0;
    both_occupied += a[i] == kOccupied && b[i] == kOccupied ? 1 : 0;
  }
  out.agreement = out.compared_cells > 0 ? static_cast<double>(out.same_class_cells) /
                                               static_cast<double>(out.compared_cells)
                                         : 1.0;
  out.occupied =
      agreementOf(both_occupied, out.candidate_occupied, both_occupied, out.reference_occupied);
  out.occupied_tolerant =
      agreementOf(matchedWithin(b, a, w, h, options.tolerance_cells), out.candidate_occupied,
                  matchedWithin(a, b, w, h, options.tolerance_cells), out.reference_occupied);
  return out;
}

}  // namespace irgs
