#pragma once
// A fixed occupancy raster, as loaded from (or exported to) a ROS map_server map.

#include <cstdint>
#include <optional>
#include <vector>

#include "core/geometry/types.hpp"

namespace irgs {

// Cell value convention follows nav_msgs/OccupancyGrid: -1 unknown, 0 free .. 100 occupied.
// Storage is row-major with row 0 at the origin (smallest y), column 0 at the smallest x;
// note the PGM file stores the top row (largest y) first, the reader/writer flips it.
struct RasterMap {
  static constexpr std::int8_t kUnknown = -1;
  static constexpr std::int8_t kFree = 0;
  static constexpr std::int8_t kOccupied = 100;

  int width = 0;
  int height = 0;
  double resolution_m = 0.05;
  // Pose of the lower-left corner of cell (0, 0) in the world. ROS ignores the yaw in practice;
  // so do we (it is kept for round trips and must be 0 for simulation).
  Pose2 origin;
  std::vector<std::int8_t> cells;  // width * height

  bool empty() const { return width <= 0 || height <= 0; }
  std::int8_t at(int col, int row) const {
    return cells[static_cast<std::size_t>(row) * static_cast<std::size_t>(width) +
                 static_cast<std::size_t>(col)];
  }
  std::int8_t& at(int col, int row) {
    return cells[static_cast<std::size_t>(row) * static_cast<std::size_t>(width) +
                 static_cast<std::size_t>(col)];
  }
  bool inside(int col, int row) const {
    return col >= 0 && row >= 0 && col < width && row < height;
  }
  // Cell containing a world point, or nothing when outside the raster.
  std::optional<std::pair<int, int>> worldToCell(const Vec2& p) const {
    const double fx = (p.x() - origin.x) / resolution_m;
    const double fy = (p.y() - origin.y) / resolution_m;
    if (fx < 0.0 || fy < 0.0)
      return std::nullopt;
    const int col = static_cast<int>(fx), row = static_cast<int>(fy);
    if (col >= width || row >= height)
      return std::nullopt;
    return std::pair{col, row};
  }
  Vec2 cellCentre(int col, int row) const {
    return {origin.x + (col + 0.5) * resolution_m, origin.y + (row + 0.5) * resolution_m};
  }
  Box2 bounds() const {
    Box2 b;
    b.extend(Vec2(origin.x, origin.y));
    b.extend(Vec2(origin.x + width * resolution_m, origin.y + height * resolution_m));
    return b;
  }
};

}  // namespace irgs
