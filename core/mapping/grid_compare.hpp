#pragma once
// Compares two occupancy grids built from the same sensor stream (a recorded run and a re-run
// with changed parameters, docs/gui.md "Re-run with parameters"): how many cells have the same
// class and how well the occupied cells agree, as precision, recall and F1 of `candidate`
// against `reference`.
//
// Cell classes: occupied when log-odds > occupied_log_odds, free when < free_log_odds, unknown
// otherwise (never observed included). The defaults (+-0.4) are those the replay end-to-end test
// uses. Grids of different resolutions are compared on a common lattice (cell size
// max(resolution a, resolution b) unless options.resolution_m is set, cells aligned to the world
// origin as the grids' own cells are): a lattice cell is occupied when any grid cell whose centre
// falls in it is occupied, else free when any is free, else unknown. With equal resolutions the
// lattice is the grids' own cells.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include "core/mapping/occupancy_grid.hpp"

namespace irgs {

struct GridCompareOptions {
  double occupied_log_odds = 0.4;
  double free_log_odds = -0.4;
  // Lattice cell size, m; 0 = the coarser of the two grids' resolutions.
  double resolution_m = 0.0;
  // Chebyshev distance (lattice cells) within which an occupied cell counts as matched for the
  // tolerant F1 (map_score.hpp uses 2 against the true map).
  int tolerance_cells = 2;
};

// Precision, recall and F1 of the candidate's occupied cells against the reference's. Both
// empty: all three are 1 (nothing to disagree on).
struct OccupiedAgreement {
  double precision = 0.0;
  double recall = 0.0;
  double f1 = 0.0;
};

struct GridComparison {
  double resolution_m = 0.0;         // lattice cell size
  bool identical = false;            // same resolution and bit-identical log-odds (operator==)
  std::size_t compared_cells = 0;    // lattice cells known (free or occupied) in either grid
  std::size_t same_class_cells = 0;  // of those, the same class in both
  std::size_t reference_only = 0;    // known in the reference, unknown in the candidate
  std::size_t candidate_only = 0;    // known in the candidate, unknown in the reference
  std::size_t reference_occupied = 0;
  std::size_t candidate_occupied = 0;
  // same_class_cells / compared_cells (1 when nothing is known in either grid).
  double agreement = 1.0;
  OccupiedAgreement occupied;           // exact lattice cells
  OccupiedAgreement occupied_tolerant;  // within tolerance_cells
};

// What is wrong with the options (thresholds not finite or free > occupied, negative
// resolution or tolerance), or nothing.
std::optional<std::string> gridCompareOptionsError(const GridCompareOptions& options);

// Throws std::invalid_argument for options gridCompareOptionsError rejects, a lattice finer than
// either grid (each grid cell must land in one lattice cell), or a union of observed areas beyond
// kMaxCompareCells lattice cells.
inline constexpr std::int64_t kMaxCompareCells = std::int64_t{1} << 28;
GridComparison compareGrids(const OccupancyGrid& reference, const OccupancyGrid& candidate,
                            const GridCompareOptions& options = {});

}  // namespace irgs
