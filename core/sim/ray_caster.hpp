#pragma once
// Ray casting against the simulated world, behind one small interface so the simulator does not
// care whether the world is vector segments or a raster, and so an indexed caster can be
// checked against (and benchmarked beside) the naive one.
//
// Casters hold scratch buffers: a caster object must not be used from two threads at once.

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "core/geometry/types.hpp"
#include "core/sim/segment_grid.hpp"

namespace irgs {

struct RayHit {
  double distance_m = 0.0;     // along the ray from its origin
  Vec2 normal = Vec2::Zero();  // unit surface normal, facing the ray's origin
  friend bool operator==(const RayHit&, const RayHit&) = default;
};

class RayCaster {
 public:
  virtual ~RayCaster() = default;

  // Nearest surface on origin + t * direction for 0 <= t <= max_range_m; `direction` must be a
  // unit vector. A surface through the origin is hit at distance 0.
  virtual std::optional<RayHit> cast(const Vec2& origin, const Vec2& direction,
                                     double max_range_m) const = 0;

  // A fan of rays from one origin (a sonar cone): hits[i] for directions[i]; the spans must
  // have the same size. The default casts each ray; indexed casters gather candidate geometry
  // once for the whole fan.
  virtual void castFan(const Vec2& origin, std::span<const Vec2> directions, double max_range_m,
                       std::span<std::optional<RayHit>> hits) const;
};

// Segments laid out for the intersection loop (a and e = b - a as separate arrays). Both segment
// casters test rays through the same function on the same numbers, so their results are
// bit-identical, and ties (two segments at exactly the same distance) go to the lower index.
class PreparedSegments {
 public:
  PreparedSegments() = default;
  explicit PreparedSegments(std::span<const Segment> segments);

  std::size_t size() const { return ax_.size(); }

  // Intersection of the ray with segment k: the distance t, or a negative value for no hit
  // (parallel, behind, beyond max_range_m, or missing the segment).
  double intersect(std::size_t k, const Vec2& origin, const Vec2& direction,
                   double max_range_m) const {
    const double ex = ex_[k], ey = ey_[k];
    const double denom = direction.x() * ey - direction.y() * ex;
    if (denom == 0.0)
      return -1.0;  // parallel (a grazing, collinear ray reflects nothing either)
    const double wx = ax_[k] - origin.x(), wy = ay_[k] - origin.y();
    const double t_num = wx * ey - wy * ex;
    const double s_num = wx * direction.y() - wy * direction.x();
    // Range tests on numerators avoid a division for the many misses.
    if (denom > 0.0) {
      if (t_num < 0.0 || s_num < 0.0 || s_num > denom)
        return -1.0;
    } else {
      if (t_num > 0.0 || s_num > 0.0 || s_num < denom)
        return -1.0;
    }
    const double t = t_num / denom;
    return t <= max_range_m ? t : -1.0;
  }

  // Unit normal of segment k facing against `direction`.
  Vec2 normalFacing(std::size_t k, const Vec2& direction) const {
    Vec2 n(-ey_[k], ex_[k]);
    n.normalize();
    return n.dot(direction) > 0.0 ? Vec2(-n) : n;
  }

 private:
  std::vector<double> ax_, ay_, ex_, ey_;
};

// Tests every segment for every ray: O(segments) per ray. The reference for tests and benchmarks.
class NaiveSegmentCaster final : public RayCaster {
 public:
  explicit NaiveSegmentCaster(std::span<const Segment> segments);
  std::optional<RayHit> cast(const Vec2& origin, const Vec2& direction,
                             double max_range_m) const override;

 private:
  PreparedSegments prepared_;
};

// Segments in a uniform grid (SegmentGrid). A single ray walks the grid cells it crosses in
// order (Amanatides–Woo) and stops once the best hit is closer than the next cell; a fan
// gathers the segments of the cells under the fan's bounding box once and tests only those.
// Results are identical to NaiveSegmentCaster.
class GridSegmentCaster final : public RayCaster {
 public:
  explicit GridSegmentCaster(std::span<const Segment> segments, double cell_size_m = 0.0);
  std::optional<RayHit> cast(const Vec2& origin, const Vec2& direction,
                             double max_range_m) const override;
  void castFan(const Vec2& origin, std::span<const Vec2> directions, double max_range_m,
               std::span<std::optional<RayHit>> hits) const override;

  const SegmentGrid& grid() const { return grid_; }

 private:
  SegmentGrid grid_;
  PreparedSegments prepared_;
  mutable std::vector<std::uint32_t> candidates_;
  mutable std::vector<std::uint32_t> visited_;  // per segment: last cast() that tested it
  mutable std::uint32_t visit_mark_ = 0;
};

}  // namespace irgs
