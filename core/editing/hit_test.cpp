#include "core/editing/hit_test.hpp"

#include <algorithm>
#include <cmath>
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
  for (std::size_t i = 0; i < map.lights.size(); ++i) {
    const auto [v, d] = nearestVertex({map.lights[i].tube.a, map.lights[i].tube.b}, p);
    consider({ElementKind::kLight, i}, v, d);
  }
  if (best)
    return best;
  // 2. The start pose, features and graph nodes (points).
  consider({ElementKind::kStart, 0}, std::nullopt, (map.start.position() - p).norm());
  if (best)
    return best;
  for (std::size_t i = 0; i < map.features.size(); ++i)
    consider({ElementKind::kFeature, i}, std::nullopt, (map.features[i].position - p).norm());
  for (std::size_t i = 0; i < map.graph.nodes.size(); ++i)
    consider({ElementKind::kNode, i}, std::nullopt, (map.graph.nodes[i].position - p).norm());
  if (best)
    return best;
  // 3. Ceiling markers (anywhere on the square) and lights (anywhere on the tube).
  for (std::size_t i = 0; i < map.markers.size(); ++i) {
    const CeilingMarker& m = map.markers[i];
    const Vec2 d = p - m.position;
    const double c = std::cos(m.heading_rad), s = std::sin(m.heading_rad);
    const double ex = std::max(std::abs(c * d.x() + s * d.y()) - 0.5 * m.size_m, 0.0);
    const double ey = std::max(std::abs(-s * d.x() + c * d.y()) - 0.5 * m.size_m, 0.0);
    consider({ElementKind::kMarker, i}, std::nullopt, std::hypot(ex, ey));
  }
  for (std::size_t i = 0; i < map.lights.size(); ++i) {
    const CeilingLight& l = map.lights[i];
    consider({ElementKind::kLight, i}, std::nullopt,
             std::max(distanceToSegment(p, l.tube.a, l.tube.b) - 0.5 * l.width_m, 0.0));
  }
  if (best)
    return best;
  // 4. Graph edges (the straight line between their nodes).
  for (std::size_t i = 0; i < map.graph.edges.size(); ++i) {
    const TopoNode* a = map.graph.node(map.graph.edges[i].from);
    const TopoNode* b = map.graph.node(map.graph.edges[i].to);
    if (a != nullptr && b != nullptr)
      consider({ElementKind::kEdge, i}, std::nullopt,
               distanceToSegment(p, a->position, b->position));
  }
  if (best)
    return best;
  // 5. Wall pieces and obstacle edges, then obstacle interiors.
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
  for (std::size_t i = 0; i < map.markers.size(); ++i)
    if (box.contains(map.markers[i].position))
      out.push_back({ElementKind::kMarker, i});
  for (std::size_t i = 0; i < map.lights.size(); ++i)
    if (box.contains(map.lights[i].tube.a) && box.contains(map.lights[i].tube.b))
      out.push_back({ElementKind::kLight, i});
  for (std::size_t i = 0; i < map.graph.nodes.size(); ++i)
    if (box.contains(map.graph.nodes[i].position))
      out.push_back({ElementKind::kNode, i});
  for (std::size_t i = 0; i < map.graph.edges.size(); ++i) {
    const TopoNode* a = map.graph.node(map.graph.edges[i].from);
    const TopoNode* b = map.graph.node(map.graph.edges[i].to);
    if (a != nullptr && b != nullptr && box.contains(a->position) && box.contains(b->position))
      out.push_back({ElementKind::kEdge, i});
  }
  return out;
}

}  // namespace irgs::editing
