#include "core/editing/hit_test.hpp"

#include <algorithm>
#include <limits>
#include <utility>

#include "core/editing/edit_geometry.hpp"

namespace irgs::editing {
namespace {

// Nearest vertex of `points` to p: (index, distance).
std::pair<std::size_t, double> nearestVertex(const std::vector<Vec2>& points, const Vec2& p) {
  std::size_t best_i = 0;
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double d = (points[i] - p).norm();
    if (d < best) {
      best = d;
      best_i = i;
    }
  }
  return {best_i, best};
}

double distanceToPolyline(const std::vector<Vec2>& points, bool closed, const Vec2& p) {
  double best = std::numeric_limits<double>::infinity();
  const std::size_t pieces = wallPieceCount(points.size(), closed);
  for (std::size_t i = 0; i < pieces; ++i)
    best = std::min(best, distanceToSegment(p, points[i], points[(i + 1) % points.size()]));
  return best;
}

}  // namespace

std::optional<Hit> hitTest(const WorldMap& map, const Vec2& p, double tolerance_m) {
  std::optional<Hit> best;
  auto consider = [&](ElementRef ref, std::optional<std::size_t> vertex, double d) {
    if (d <= tolerance_m && (!best || d < best->distance_m))
      best = Hit{ref, vertex, d};
  };
  // 1. Vertices.
  for (std::size_t i = 0; i < map.walls.size(); ++i) {
    const auto [v, d] = nearestVertex(map.walls[i].points, p);
    consider({ElementKind::kWall, i}, v, d);
  }
  for (std::size_t i = 0; i < map.obstacles.size(); ++i) {
    const auto [v, d] = nearestVertex(map.obstacles[i].polygon, p);
    consider({ElementKind::kObstacle, i}, v, d);
  }
  if (best)
    return best;
  // 2. The start pose and features (points).
  consider({ElementKind::kStart, 0}, std::nullopt, (map.start.position() - p).norm());
  if (best)
    return best;
  for (std::size_t i = 0; i < map.features.size(); ++i)
    consider({ElementKind::kFeature, i}, std::nullopt, (map.features[i].position - p).norm());
  if (best)
    return best;
  // 3. Wall pieces and obstacle edges, then obstacle interiors.
  for (std::size_t i = 0; i < map.walls.size(); ++i)
    consider({ElementKind::kWall, i}, std::nullopt,
             distanceToPolyline(map.walls[i].points, map.walls[i].closed, p));
  for (std::size_t i = 0; i < map.obstacles.size(); ++i) {
    const auto& poly = map.obstacles[i].polygon;
    consider({ElementKind::kObstacle, i}, std::nullopt,
             polygonContains(poly, p) ? 0.0 : distanceToPolyline(poly, true, p));
  }
  return best;
}

std::vector<ElementRef> elementsInBox(const WorldMap& map, const Box2& box) {
  std::vector<ElementRef> out;
  auto allInside = [&](const std::vector<Vec2>& points) {
    if (points.empty())
      return false;
    for (const Vec2& q : points)
      if (!box.contains(q))
        return false;
    return true;
  };
  for (std::size_t i = 0; i < map.walls.size(); ++i)
    if (allInside(map.walls[i].points))
      out.push_back({ElementKind::kWall, i});
  for (std::size_t i = 0; i < map.obstacles.size(); ++i)
    if (allInside(map.obstacles[i].polygon))
      out.push_back({ElementKind::kObstacle, i});
  for (std::size_t i = 0; i < map.features.size(); ++i)
    if (box.contains(map.features[i].position))
      out.push_back({ElementKind::kFeature, i});
  if (box.contains(map.start.position()))
    out.push_back({ElementKind::kStart, 0});
  return out;
}

}  // namespace irgs::editing
