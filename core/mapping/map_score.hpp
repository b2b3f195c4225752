#pragma once
// Scores a built occupancy grid against the true map: occupied cells of the built map against
// the true surfaces, each side matched within a tolerance of a few cells, as precision, recall
// and F1 (issue 4 acceptance: 2-cell tolerance).
//
// Ground truth: the map rasterised at the scoring resolution (walls by supercover, obstacles
// filled; a raster layer's occupied and unknown cells), reduced to its SURFACE cells — blocked
// cells with a 4-neighbour in the free space reachable from the start pose (a flood fill). Faces
// that no robot in the start's free space can ever see (the far side of the outer wall, closed
// rooms) are not part of the truth. Built map: the 1 cm cells whose occupancy probability is
// above the threshold, each marking its scoring cell occupied.

#include <cstddef>
#include <optional>
#include <string>

#include "core/mapping/occupancy_grid.hpp"
#include "core/planning/planning_grid.hpp"
#include "core/world/world_map.hpp"

namespace irgs {

struct MapScoreOptions {
  double resolution_m = 0.05;          // scoring cell (vector maps; a raster map uses its own)
  int tolerance_cells = 2;             // Chebyshev distance for a match
  double occupied_probability = 0.65;  // built cell occupied above this
};

struct MapScore {
  double precision = 0.0;  // built occupied cells near a true surface / built occupied cells
  double recall = 0.0;     // true surface cells near a built occupied cell / true surface cells
  double f1 = 0.0;
  std::size_t built_cells = 0;  // occupied scoring cells of the built map
  std::size_t truth_cells = 0;  // true surface cells
  double resolution_m = 0.0;
};

// The true surface cells (1) of `map` as seen from `start`. Throws std::invalid_argument for a
// map without walls, obstacles or raster, a bad resolution, or a start outside the map's grid.
PlanningGrid trueSurfaceGrid(const WorldMap& map, const Pose2& start, double resolution_m);

// Scores `built` against `truth` (from trueSurfaceGrid). Throws std::invalid_argument for a
// negative tolerance or a threshold outside (0, 1).
MapScore scoreMap(const OccupancyGrid& built, const PlanningGrid& truth,
                  const MapScoreOptions& options = {});

// trueSurfaceGrid + scoreMap.
MapScore scoreMap(const OccupancyGrid& built, const WorldMap& map, const Pose2& start,
                  const MapScoreOptions& options = {});

}  // namespace irgs
