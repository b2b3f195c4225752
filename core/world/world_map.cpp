#include "core/world/world_map.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace irgs {
namespace {

double distanceToSegment(const Vec2& p, const Segment& s) {
  const Vec2 d = s.b - s.a;
  const double len2 = d.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((p - s.a).dot(d) / len2, 0.0, 1.0) : 0.0;
  return (s.a + t * d - p).norm();
}

bool pointInPolygon(const Vec2& p, const std::vector<Vec2>& polygon) {
  const std::size_t n = polygon.size();
  if (n < 3)
    return false;
  bool inside = false;
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    const Vec2& a = polygon[i];
    const Vec2& b = polygon[j];
    if (distanceToSegment(p, {a, b}) <= 1e-12)
      return true;
    if ((a.y() > p.y()) != (b.y() > p.y()) &&
        p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x())
      inside = !inside;
  }
  return inside;
}

}  // namespace

std::vector<WorldMap::LabelledSegment> WorldMap::labelledSegments() const {
  std::vector<LabelledSegment> out;
  for (const Wall& wall : walls) {
    for (std::size_t i = 0; i + 1 < wall.points.size(); ++i) {
      out.push_back({{wall.points[i], wall.points[i + 1]}, wall.id});
    }
    if (wall.closed && wall.points.size() > 2)
      out.push_back({{wall.points.back(), wall.points[0]}, wall.id});
  }
  for (const Obstacle& obstacle : obstacles) {
    const auto& poly = obstacle.polygon;
    for (std::size_t i = 0; i < poly.size() && poly.size() > 1; ++i) {
      out.push_back({{poly[i], poly[(i + 1) % poly.size()]}, obstacle.id});
    }
  }
  return out;
}

std::vector<Segment> WorldMap::segments() const {
  std::vector<Segment> out;
  for (LabelledSegment& labelled : labelledSegments())
    out.push_back(labelled.segment);
  return out;
}

Box2 WorldMap::bounds() const {
  Box2 box;
  for (const Wall& wall : walls) {
    for (const Vec2& p : wall.points)
      box.extend(p);
  }
  for (const Obstacle& obstacle : obstacles) {
    for (const Vec2& p : obstacle.polygon)
      box.extend(p);
  }
  for (const PointFeature& f : features)
    box.extend(f.position);
  for (const CeilingMarker& m : markers)
    box.extend(m.position);
  for (const CeilingLight& l : lights) {
    box.extend(l.tube.a);
    box.extend(l.tube.b);
  }
  for (const TopoNode& n : graph.nodes)
    box.extend(n.position);
  if (raster && !raster->raster.empty())
    box.extend(raster->raster.bounds());
  return box;
}

const Obstacle* WorldMap::obstacleAt(const Vec2& p) const {
  for (const Obstacle& obstacle : obstacles) {
    if (pointInPolygon(p, obstacle.polygon))
      return &obstacle;
  }
  return nullptr;
}

double WorldMap::distanceToNearestSegment(const Vec2& p) const {
  double best = std::numeric_limits<double>::infinity();
  for (const Segment& s : segments())
    best = std::min(best, distanceToSegment(p, s));
  return best;
}

}  // namespace irgs
