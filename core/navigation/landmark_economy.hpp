#pragma once
// Landmark economy of 002_… Fig. 22: how many ceiling landmarks a floor needs when only
// artificial markers localize the robot, against markers at the graph nodes plus the existing
// ceiling lights along the corridors (the paper's mixed map).
//
// Model (the paper prints counts, not the rule; see docs/decisions.md):
// * artificial only: every point of the free floor must lie in the square cell of some marker,
//   cells `marker_cell_m` on a side on a lattice over the floor (the patch of ceiling the
//   camera sees precisely when looking up); a cell that holds any free floor needs a marker,
//   so crossing corridors share the markers of their common square.
// * mixed: one marker per graph node (junctions, corners, dead ends) and one light every
//   `light_spacing_m` along each edge, the stretch `node_clear_m` around each node left to the
//   node's marker.

#include <vector>

namespace irgs {

// A grid of corridors: `cols` x `rows` blocks of `block_m` between corridor centre lines, each
// corridor `corridor_width_m` wide; (cols + 1) x (rows + 1) junction nodes.
struct CorridorFloorSpec {
  int cols = 1;
  int rows = 1;
  double block_m = 8.0;
  double corridor_width_m = 2.0;
};

struct EconomyParams {
  double marker_cell_m = 1.0;
  double light_spacing_m = 2.0;
  double node_clear_m = 1.0;
  double raster_m = 0.05;  // resolution of the free-area raster
};

struct EconomyRow {
  CorridorFloorSpec floor;
  double free_area_m2 = 0.0;
  int nodes = 0;
  int edges = 0;
  int artificial_markers = 0;  // artificial-only map
  int mixed_markers = 0;       // mixed map: markers ...
  int mixed_lights = 0;        // ... plus lights
};

// Counts for one generated floor. Throws std::invalid_argument for a floor with no blocks or
// non-positive sizes.
EconomyRow landmarkEconomy(const CorridorFloorSpec& floor, const EconomyParams& params);

// The floors of the default table: 1 x 1 up to 4 x 3 blocks of 4 m.
std::vector<CorridorFloorSpec> defaultEconomyFloors();

}  // namespace irgs
