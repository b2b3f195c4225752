#include "core/world/world_map.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/geometry/geometry_queries.hpp"

namespace irgs {
namespace {

// Inside or on the boundary.
bool insideOrOnPolygon(const Vec2& p, const std::vector<Vec2>& polygon) {
  if (polygon.size() < 3)
    return false;
  for (std::size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++)
    if (pointSegmentDistance(p, polygon[i], polygon[j]) <= 1e-12)
      return true;
  return pointInPolygon(p, polygon);
}

}  // namespace

std::optional<ColourRgb> parseHexColour(std::string_view text) {
  if (text.size() != 7 || text[0] != '#')
    return std::nullopt;
  int v[6];
  for (std::size_t i = 0; i < 6; ++i) {
    const char c = text[i + 1];
    if (c >= '0' && c <= '9')
      v[i] = c - '0';
    else if (c >= 'a' && c <= 'f')
      v[i] = c - 'a' + 10;
    else if (c >= 'A' && c <= 'F')
      v[i] = c - 'A' + 10;
    else
      return std::nullopt;
  }
  return ColourRgb{v[0] * 16 + v[1], v[2] * 16 + v[3], v[4] * 16 + v[5]};
}

std::string formatHexColour(const ColourRgb& colour) {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string out = "#";
  for (int c : {colour.r, colour.g, colour.b}) {
    c = std::clamp(c, 0, 255);
    out += kDigits[c / 16];
    out += kDigits[c % 16];
  }
  return out;
}

const TopoNode* TopoGraph::node(const std::string& id) const {
  for (const TopoNode& n : nodes)
    if (n.id == id)
      return &n;
  return nullptr;
}

std::optional<double> TopoGraph::edgeCost(const TopoEdge& edge) const {
  const TopoNode* a = node(edge.from);
  const TopoNode* b = node(edge.to);
  if (a == nullptr || b == nullptr)
    return std::nullopt;
  return edge.cost_m ? *edge.cost_m : (b->position - a->position).norm();
}

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
    if (insideOrOnPolygon(p, obstacle.polygon))
      return &obstacle;
  }
  return nullptr;
}

double WorldMap::distanceToNearestSegment(const Vec2& p) const {
  double best = std::numeric_limits<double>::infinity();
  for (const Segment& s : segments())
    best = std::min(best, pointSegmentDistance(p, s.a, s.b));
  return best;
}

}  // namespace irgs
