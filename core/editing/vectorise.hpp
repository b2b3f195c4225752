#pragma once
// "Vectorise" a raster layer (a ROS map) into walls: the outline of every occupied region,
// traced along cell borders and simplified, becomes a closed wall. Pure and deterministic.
//
// Tracing: every side between an occupied cell and a non-occupied one (free, unknown or outside
// the raster) is a directed edge with the occupied cell on its left; edges chain into closed
// loops (counter-clockwise around a blob, clockwise around a hole; at a vertex shared by two
// diagonal cells the left turn is taken, so diagonal neighbours stay separate outlines). Runs of
// collinear edges merge, then Ramer-Douglas-Peucker with `tolerance_m` removes the staircase of
// slanted borders. Outlines smaller than `min_size_m` (bounding-box diagonal) are speckle and
// dropped. A wall 3 cells thick gives one closed outline around it: both faces are walls, which
// is what the sonar model needs.

#include <cstdint>
#include <vector>

#include "core/editing/map_edit.hpp"
#include "core/world/raster_map.hpp"

namespace irgs::editing {

struct VectoriseSettings {
  std::int8_t occupied_threshold = 65;  // cells >= this are occupied (ROS occupied_thresh 0.65)
  double tolerance_m = 0.0;             // RDP tolerance; 0 = one cell
  double min_size_m = 0.0;              // outlines smaller than this are dropped; 0 = 3 cells
};

// Closed outlines (first point not repeated) in world metres, in raster scan order of their
// first cell. The raster's origin yaw is ignored (as ROS does). Throws std::invalid_argument for
// a raster whose cell count does not match its size, a non-positive resolution or negative
// settings.
std::vector<std::vector<Vec2>> traceOccupiedOutlines(const RasterMap& raster,
                                                     const VectoriseSettings& settings = {});

// One undoable edit adding the outlines of `map.raster` as closed walls ("raster-1", ...),
// selecting them. Empty when the map has no raster or nothing is occupied.
Edit vectoriseRaster(const WorldMap& map, const VectoriseSettings& settings = {});

}  // namespace irgs::editing
