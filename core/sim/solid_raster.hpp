#pragma once
// The raster layer of a world as solid/empty cells, with the queries the simulator needs: ray
// casting (Amanatides–Woo DDA), polygon overlap, clearance and "is anything near this segment".
//
// Which cells are solid: value >= occupied_threshold, and unknown cells (-1) when
// unknown_is_solid (the default: a ROS map is surrounded by unknown space, and a robot should
// neither see through nor drive into space nobody has observed). Outside the raster rectangle
// there is nothing: a map that wants a closed boundary draws it. The raster's origin yaw is
// ignored (as ROS does).

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "core/sim/ray_caster.hpp"
#include "core/world/raster_map.hpp"

namespace irgs {

struct RasterSolidity {
  int occupied_threshold = 65;  // ROS map_server's default occupied_thresh 0.65, in percent
  bool unknown_is_solid = true;
};

class SolidRaster {
 public:
  SolidRaster(const RasterMap& raster, RasterSolidity solidity);

  int width() const { return width_; }
  int height() const { return height_; }
  double resolution() const { return res_; }
  bool solid(int col, int row) const {
    return col >= 0 && row >= 0 && col < width_ && row < height_ && solid_[index(col, row)] != 0;
  }
  Box2 cellBox(int col, int row) const;

  std::optional<RayHit> cast(const Vec2& origin, const Vec2& direction, double max_range_m) const;
  // True when the polygon shares a point with a solid cell.
  bool polygonTouches(std::span<const Vec2> polygon) const;
  // A lower bound of the distance from p to the nearest solid cell (from a precomputed
  // Euclidean distance transform), at most cap_m; exact enough for "can the robot touch
  // anything before it moves this far".
  double clearanceLowerBound(const Vec2& p, double cap_m) const;
  // True when a solid cell lies within distance_m of the segment ab.
  bool segmentWithin(const Vec2& a, const Vec2& b, double distance_m) const;

 private:
  std::size_t index(int col, int row) const {
    return static_cast<std::size_t>(row) * static_cast<std::size_t>(width_) +
           static_cast<std::size_t>(col);
  }
  Vec2 surfaceNormal(int col, int row, const Vec2& face_normal, const Vec2& direction) const;
  void computeDistanceTransform();

  int width_ = 0;
  int height_ = 0;
  double res_ = 0.05;
  Vec2 origin_ = Vec2::Zero();
  std::vector<std::uint8_t> solid_;
  std::vector<float> distance_cells_;  // distance to the nearest solid cell centre, in cells
};

// RayCaster view of a SolidRaster (which must outlive it).
class RasterCaster final : public RayCaster {
 public:
  explicit RasterCaster(const SolidRaster& raster) : raster_(raster) {}
  std::optional<RayHit> cast(const Vec2& origin, const Vec2& direction,
                             double max_range_m) const override {
    return raster_.cast(origin, direction, max_range_m);
  }

 private:
  const SolidRaster& raster_;
};

}  // namespace irgs
