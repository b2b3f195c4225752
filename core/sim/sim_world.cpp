#include "core/sim/sim_world.hpp"

#include <algorithm>

#include "core/geometry/geometry_queries.hpp"

namespace irgs {

SimWorld::SimWorld(const WorldMap& map, SimWorldOptions options) : grid_(map.segments()) {
  if (options.segment_caster == SegmentCasterKind::kNaive)
    segment_caster_ = std::make_unique<NaiveSegmentCaster>(grid_.segments());
  else
    segment_caster_ = std::make_unique<GridSegmentCaster>(grid_.segments());
  if (map.raster && !map.raster->raster.empty())
    raster_ = std::make_unique<SolidRaster>(map.raster->raster, options.raster);
}

void SimWorld::setMovingPolygons(std::span<const std::vector<Vec2>> polygons) {
  moving_segments_.clear();
  for (const auto& polygon : polygons) {
    for (std::size_t i = 0; i < polygon.size(); ++i)
      moving_segments_.push_back({polygon[i], polygon[(i + 1) % polygon.size()]});
  }
  moving_ = PreparedSegments(moving_segments_);
}

namespace {

// The nearer of `hit` and the nearest moving segment on the ray.
void castMoving(const PreparedSegments& moving, const Vec2& origin, const Vec2& direction,
                double max_range_m, std::optional<RayHit>& hit) {
  for (std::size_t k = 0; k < moving.size(); ++k) {
    const double limit = hit ? hit->distance_m : max_range_m;
    const double t = moving.intersect(k, origin, direction, limit);
    if (t >= 0.0 && (!hit || t < hit->distance_m))
      hit = RayHit{t, moving.normalFacing(k, direction)};
  }
}

}  // namespace

std::optional<RayHit> SimWorld::cast(const Vec2& origin, const Vec2& direction,
                                     double max_range_m) const {
  std::optional<RayHit> hit = segment_caster_->cast(origin, direction, max_range_m);
  castMoving(moving_, origin, direction, max_range_m, hit);
  if (raster_) {
    const double limit = hit ? hit->distance_m : max_range_m;
    if (auto raster_hit = raster_->cast(origin, direction, limit);
        raster_hit && (!hit || raster_hit->distance_m < hit->distance_m))
      hit = raster_hit;
  }
  return hit;
}

void SimWorld::castFan(const Vec2& origin, std::span<const Vec2> directions, double max_range_m,
                       std::span<std::optional<RayHit>> hits) const {
  segment_caster_->castFan(origin, directions, max_range_m, hits);
  for (std::size_t i = 0; i < directions.size() && moving_.size() > 0; ++i)
    castMoving(moving_, origin, directions[i], max_range_m, hits[i]);
  if (!raster_)
    return;
  for (std::size_t i = 0; i < directions.size(); ++i) {
    const double limit = hits[i] ? hits[i]->distance_m : max_range_m;
    if (auto raster_hit = raster_->cast(origin, directions[i], limit);
        raster_hit && (!hits[i] || raster_hit->distance_m < hits[i]->distance_m))
      hits[i] = raster_hit;
  }
}

bool SimWorld::polygonTouches(std::span<const Vec2> polygon) const {
  if (polygon.empty())
    return false;
  for (const Segment& m : moving_segments_) {
    if (polygonTouchesSegment(polygon, m.a, m.b))
      return true;
  }
  Box2 box = boundsOf(polygon);
  box.min -= Vec2::Constant(SegmentGrid::kMargin_m);
  box.max += Vec2::Constant(SegmentGrid::kMargin_m);
  grid_.gather(box, candidates_);
  const auto& segments = grid_.segments();
  for (const std::uint32_t k : candidates_) {
    if (polygonTouchesSegment(polygon, segments[k].a, segments[k].b))
      return true;
  }
  return raster_ && raster_->polygonTouches(polygon);
}

double SimWorld::clearanceLowerBound(const Vec2& p, double cap_m) const {
  double best = cap_m;
  for (const Segment& m : moving_segments_)
    best = std::min(best, pointSegmentDistance(p, m.a, m.b));
  Box2 box;
  box.extend(p);
  box.min -= Vec2::Constant(cap_m);
  box.max += Vec2::Constant(cap_m);
  grid_.gather(box, candidates_);
  const auto& segments = grid_.segments();
  for (const std::uint32_t k : candidates_)
    best = std::min(best, pointSegmentDistance(p, segments[k].a, segments[k].b));
  if (raster_)
    best = std::min(best, raster_->clearanceLowerBound(p, cap_m));
  return best;
}

bool SimWorld::segmentWithin(const Vec2& a, const Vec2& b, double distance_m) const {
  for (const Segment& m : moving_segments_) {
    if (segmentSegmentDistance(a, b, m.a, m.b) <= distance_m)
      return true;
  }
  Box2 box;
  box.extend(a);
  box.extend(b);
  box.min -= Vec2::Constant(distance_m + SegmentGrid::kMargin_m);
  box.max += Vec2::Constant(distance_m + SegmentGrid::kMargin_m);
  grid_.gather(box, candidates_);
  const auto& segments = grid_.segments();
  for (const std::uint32_t k : candidates_) {
    if (segmentSegmentDistance(a, b, segments[k].a, segments[k].b) <= distance_m)
      return true;
  }
  return raster_ && raster_->segmentWithin(a, b, distance_m);
}

}  // namespace irgs
