#include "core/world/world_map.hpp"

namespace irgs {

std::vector<Segment> WorldMap::segments() const {
  std::vector<Segment> out;
  for (const Wall& wall : walls) {
    for (std::size_t i = 0; i + 1 < wall.points.size(); ++i) {
      out.push_back({wall.points[i], wall.points[i + 1]});
    }
    if (wall.closed && wall.points.size() > 2)
      out.push_back({wall.points.back(), wall.points[0]});
  }
  for (const Obstacle& obstacle : obstacles) {
    const auto& poly = obstacle.polygon;
    for (std::size_t i = 0; i < poly.size() && poly.size() > 1; ++i) {
      out.push_back({poly[i], poly[(i + 1) % poly.size()]});
    }
  }
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

}  // namespace irgs
