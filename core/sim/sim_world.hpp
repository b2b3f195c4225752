#pragma once
// The simulator's view of a WorldMap: every reflecting/solid thing (wall and obstacle segments,
// and the raster layer's solid cells) behind ray casting and the collision, clearance and
// contact queries. Built once per map; queries are cheap and allocation-free after warm-up.
// Holds scratch buffers: not for concurrent use.

#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "core/sim/ray_caster.hpp"
#include "core/sim/segment_grid.hpp"
#include "core/sim/solid_raster.hpp"
#include "core/world/world_map.hpp"

namespace irgs {

// Which ray caster handles the vector segments. kNaive exists as the benchmark and test
// reference; collision and contact queries always use the grid index.
enum class SegmentCasterKind { kIndexed, kNaive };

struct SimWorldOptions {
  SegmentCasterKind segment_caster = SegmentCasterKind::kIndexed;
  RasterSolidity raster;
};

class SimWorld {
 public:
  SimWorld(const WorldMap& map, SimWorldOptions options);
  SimWorld(const SimWorld&) = delete;
  SimWorld& operator=(const SimWorld&) = delete;

  // Nearest surface of segments and raster (a segment wins an exact tie).
  std::optional<RayHit> cast(const Vec2& origin, const Vec2& direction, double max_range_m) const;
  void castFan(const Vec2& origin, std::span<const Vec2> directions, double max_range_m,
               std::span<std::optional<RayHit>> hits) const;

  // True when the polygon (world frame) shares a point with a segment or a solid cell.
  bool polygonTouches(std::span<const Vec2> polygon) const;
  // A lower bound of the distance from p to the nearest geometry, at most cap_m.
  double clearanceLowerBound(const Vec2& p, double cap_m) const;
  // True when some geometry lies within distance_m of the segment ab.
  bool segmentWithin(const Vec2& a, const Vec2& b, double distance_m) const;

  // The moving obstacles' outlines (world frame) at the current time; every query above sees
  // them from now on, until the next call. Few and small, so they are tested without an index.
  void setMovingPolygons(std::span<const std::vector<Vec2>> polygons);
  bool hasMovingObstacles() const { return moving_.size() > 0; }

  std::size_t segmentCount() const { return grid_.segments().size(); }
  bool hasRaster() const { return raster_ != nullptr; }

 private:
  SegmentGrid grid_;
  std::unique_ptr<RayCaster> segment_caster_;
  std::unique_ptr<SolidRaster> raster_;
  mutable std::vector<std::uint32_t> candidates_;
  std::vector<Segment> moving_segments_;
  PreparedSegments moving_;
};

}  // namespace irgs
