#include "core/estimation/localization_map.hpp"

namespace irgs {

LocalizationMap buildLocalizationMap(const WorldMap& map) {
  LocalizationMap out;
  auto add = [&out](const Vec2& a, const Vec2& b, const std::string& id) {
    const Segment seg{a, b};
    if (!(seg.length() > 0.0))
      return;
    for (const WallLine& line : wallLineFaces(seg))
      out.walls.push_back({id, line, robotFacing(line), seg});
  };
  for (const Wall& wall : map.walls) {
    for (std::size_t i = 0; i + 1 < wall.points.size(); ++i)
      add(wall.points[i], wall.points[i + 1], wall.id);
    if (wall.closed && wall.points.size() > 2)
      add(wall.points.back(), wall.points.front(), wall.id);
  }
  for (const Obstacle& obstacle : map.obstacles) {
    const auto& poly = obstacle.polygon;
    for (std::size_t i = 0; poly.size() > 1 && i < poly.size(); ++i)
      add(poly[i], poly[(i + 1) % poly.size()], obstacle.id);
  }
  for (const PointFeature& f : map.features)
    out.points.push_back({f.id, f.kind, f.position});
  return out;
}

}  // namespace irgs
