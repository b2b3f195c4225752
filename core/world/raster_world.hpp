#pragma once
// A WorldMap around a raster (a ROS map) and a safe start pose on it.

#include <string>

#include "core/world/raster_map.hpp"
#include "core/world/world_map.hpp"

namespace irgs {

// A cell is free when its value is 0..49; unknown (-1) and 50..100 block. Outside the raster
// counts as unknown.
inline bool isFreeCell(std::int8_t value) {
  return value >= 0 && value < 50;
}

struct StartPoseSearch {
  Pose2 pose;                // heading 0
  double clearance_m = 0.0;  // distance from the pose to the nearest blocking cell or the edge
  bool found = false;        // a free cell with the requested clearance exists
};

// The centre of the free cell nearest the world origin whose clearance is at least
// `clearance_m`. Clearance comes from an exact Euclidean distance transform (Felzenszwalb &
// Huttenlocher) over blocking cells, measured from the cell centre to the nearest blocking
// cell's edge, and capped by the distance to the raster's edge; O(cells). Without such a cell:
// the free cell with the largest clearance (found = false); with no free cell at all, the centre
// of the raster (found = false, clearance 0).
StartPoseSearch findStartPose(const RasterMap& raster, double clearance_m = 0.25);

// A map that holds only `raster` as its raster layer (`source` is recorded as the layer's
// source and, by its file stem, as the map name), with the start pose from findStartPose.
// `search`, when given, receives the start-pose search result.
WorldMap worldFromRaster(RasterMap raster, const std::string& source, double clearance_m = 0.25,
                         StartPoseSearch* search = nullptr);

}  // namespace irgs
