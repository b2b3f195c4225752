#include "core/editing/validation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <map>
#include <set>
#include <stdexcept>

#include "core/editing/edit_geometry.hpp"

namespace irgs::editing {
namespace {

std::string metres(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f m", v);
  return buf;
}

double distanceToPieces(const std::vector<Vec2>& pts, bool closed, const Vec2& p,
                        std::size_t skip_from, std::size_t skip_to) {
  double best = std::numeric_limits<double>::infinity();
  const std::size_t pieces = wallPieceCount(pts.size(), closed);
  for (std::size_t i = 0; i < pieces; ++i) {
    if (i >= skip_from && i < skip_to)
      continue;
    best = std::min(best, distanceToSegment(p, pts[i], pts[(i + 1) % pts.size()]));
  }
  return best;
}

struct Nearest {
  double distance = std::numeric_limits<double>::infinity();
  std::optional<ElementRef> ref;
};

Vec2 closestOnSegment(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double len2 = ab.squaredNorm();
  if (len2 <= 0.0)
    return a;
  return a + std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) * ab;
}

// The nearest wall piece to the end of wall `wi` at point index `end`, among the other walls and
// the wall's own pieces that do not contain this end. Joined ends have distance ~0. A piece that
// only lies behind the end (back along the wall) cannot be a gap the wall stops short of: a
// short stub standing off a wall is not an unclosed outline.
Nearest nearestToEnd(const WorldMap& map, std::size_t wi, std::size_t end, double join_m) {
  const Wall& wall = map.walls[wi];
  const Vec2& p = wall.points[end];
  const Vec2& inner = wall.points[end == 0 ? 1 : end - 1];
  const Vec2 outward = p - inner;
  Nearest n;
  for (std::size_t j = 0; j < map.walls.size(); ++j) {
    const Wall& other = map.walls[j];
    const std::size_t pieces = wallPieceCount(other.points.size(), other.closed);
    const std::size_t skip = j != wi ? pieces : (end == 0 ? 0 : pieces - 1);
    for (std::size_t k = 0; k < pieces; ++k) {
      if (k == skip)
        continue;
      const Vec2 q =
          closestOnSegment(p, other.points[k], other.points[(k + 1) % other.points.size()]);
      const double d = (q - p).norm();
      if (d > join_m && (q - p).dot(outward) <= 0.0)
        continue;  // behind the end
      if (d < n.distance)
        n = {d, ElementRef{ElementKind::kWall, j}};
    }
  }
  return n;
}

// Distance from p to the nearest obstacle edge (0 inside an obstacle).
double distanceToObstacles(const WorldMap& map, const Vec2& p) {
  double best = std::numeric_limits<double>::infinity();
  for (const Obstacle& o : map.obstacles)
    best = std::min(
        best, polygonContains(o.polygon, p) ? 0.0 : distanceToPieces(o.polygon, true, p, 0, 0));
  return best;
}

void checkOutlines(const WorldMap& map, const ValidationSettings& s, std::vector<MapIssue>& out) {
  for (std::size_t wi = 0; wi < map.walls.size(); ++wi) {
    const Wall& wall = map.walls[wi];
    if (wall.closed || wall.points.size() < 2)
      continue;
    const std::size_t last = wall.points.size() - 1;
    if ((wall.points.front() - wall.points.back()).norm() <= s.join_tolerance_m)
      continue;  // closed by coinciding ends
    bool free_end[2] = {false, false};
    const std::size_t ends[2] = {0, last};
    for (int e = 0; e < 2; ++e) {
      const Nearest n = nearestToEnd(map, wi, ends[e], s.join_tolerance_m);
      // An end on a wall or against an obstacle is joined. Only a wall nearby makes a gap: an
      // end short of furniture is a wall that stops, not an outline left open.
      if (n.distance <= s.join_tolerance_m ||
          distanceToObstacles(map, wall.points[ends[e]]) <= s.join_tolerance_m)
        continue;
      if (n.distance <= s.gap_tolerance_m) {
        // Two ends facing each other across one gap: report the gap once.
        const ElementRef self{ElementKind::kWall, wi};
        const bool seen = std::any_of(out.begin(), out.end(), [&](const MapIssue& other) {
          return other.kind == IssueKind::kUnclosedOutline && other.elements.size() == 2 &&
                 other.elements[0] == *n.ref && other.elements[1] == self &&
                 (other.position - wall.points[ends[e]]).norm() <= s.gap_tolerance_m;
        });
        if (seen)
          continue;
        MapIssue issue;
        issue.kind = IssueKind::kUnclosedOutline;
        issue.elements = {ElementRef{ElementKind::kWall, wi}};
        if (n.ref && !(*n.ref == issue.elements.front()))
          issue.elements.push_back(*n.ref);
        issue.position = wall.points[ends[e]];
        issue.message = "wall '" + wall.id + "' ends " + metres(n.distance) +
                        " short of another wall: the outline is not closed";
        out.push_back(std::move(issue));
      } else {
        free_end[e] = true;
      }
    }
    if (free_end[0] && free_end[1] && wall.points.size() >= 3) {
      MapIssue issue;
      issue.kind = IssueKind::kUnclosedOutline;
      issue.elements = {ElementRef{ElementKind::kWall, wi}};
      issue.position = wall.points.back();
      issue.message = "wall '" + wall.id +
                      "' is an open outline: its ends touch nothing (close it or join them)";
      out.push_back(std::move(issue));
    }
  }
}

void checkOverlaps(const WorldMap& map, const ValidationSettings& s, std::vector<MapIssue>& out) {
  for (std::size_t i = 0; i < map.features.size(); ++i) {
    for (std::size_t j = i + 1; j < map.features.size(); ++j) {
      const double d = (map.features[i].position - map.features[j].position).norm();
      if (d < s.feature_separation_m) {
        MapIssue issue;
        issue.kind = IssueKind::kOverlappingFeatures;
        issue.elements = {ElementRef{ElementKind::kFeature, i},
                          ElementRef{ElementKind::kFeature, j}};
        issue.position = map.features[i].position;
        issue.message = "features '" + map.features[i].id + "' and '" + map.features[j].id +
                        "' overlap (" + metres(d) + " apart)";
        out.push_back(std::move(issue));
      }
    }
  }
  for (std::size_t i = 0; i < map.obstacles.size(); ++i) {
    for (std::size_t j = i + 1; j < map.obstacles.size(); ++j) {
      if (polygonsOverlap(map.obstacles[i].polygon, map.obstacles[j].polygon)) {
        MapIssue issue;
        issue.kind = IssueKind::kOverlappingObstacles;
        issue.elements = {ElementRef{ElementKind::kObstacle, i},
                          ElementRef{ElementKind::kObstacle, j}};
        Box2 box;
        box.extend(elementBounds(map.obstacles[i]));
        box.extend(elementBounds(map.obstacles[j]));
        issue.position = (box.min + box.max) / 2.0;
        issue.message =
            "obstacles '" + map.obstacles[i].id + "' and '" + map.obstacles[j].id + "' overlap";
        out.push_back(std::move(issue));
      }
    }
  }
}

void checkStart(const WorldMap& map, const ValidationSettings& s, std::vector<MapIssue>& out) {
  const Vec2 p = map.start.position();
  MapIssue issue;
  issue.kind = IssueKind::kStartInWall;
  issue.severity = Severity::kError;
  issue.position = p;
  for (std::size_t i = 0; i < map.obstacles.size(); ++i) {
    if (polygonContains(map.obstacles[i].polygon, p)) {
      issue.elements = {ElementRef{ElementKind::kStart, 0}, ElementRef{ElementKind::kObstacle, i}};
      issue.message = "the start pose is inside obstacle '" + map.obstacles[i].id + "'";
      out.push_back(std::move(issue));
      return;
    }
  }
  Nearest n;
  for (std::size_t i = 0; i < map.walls.size(); ++i) {
    const double d = distanceToPieces(map.walls[i].points, map.walls[i].closed, p, 0, 0);
    if (d < n.distance)
      n = {d, ElementRef{ElementKind::kWall, i}};
  }
  for (std::size_t i = 0; i < map.obstacles.size(); ++i) {
    const double d = distanceToPieces(map.obstacles[i].polygon, true, p, 0, 0);
    if (d < n.distance)
      n = {d, ElementRef{ElementKind::kObstacle, i}};
  }
  if (n.ref && n.distance < s.robot_radius_m) {
    issue.elements = {ElementRef{ElementKind::kStart, 0}, *n.ref};
    issue.message = "the start pose is " + metres(n.distance) + " from " +
                    describe(elementAt(map, *n.ref)) + ": the robot (radius " +
                    metres(s.robot_radius_m) + ") would start inside it";
    out.push_back(std::move(issue));
  }
}

void checkDegenerate(const WorldMap& map, const ValidationSettings& s, std::vector<MapIssue>& out) {
  for (std::size_t i = 0; i < map.walls.size(); ++i) {
    const Wall& w = map.walls[i];
    double length = 0.0;
    for (std::size_t k = 0; k + 1 < w.points.size(); ++k)
      length += (w.points[k + 1] - w.points[k]).norm();
    if (w.points.size() < 2 || length <= s.join_tolerance_m) {
      MapIssue issue;
      issue.kind = IssueKind::kDegenerateElement;
      issue.elements = {ElementRef{ElementKind::kWall, i}};
      issue.position = w.points.empty() ? Vec2::Zero() : w.points.front();
      issue.message = "wall '" + w.id + "' has no length";
      out.push_back(std::move(issue));
    }
  }
  for (std::size_t i = 0; i < map.obstacles.size(); ++i) {
    const Obstacle& o = map.obstacles[i];
    const double area = std::abs(signedArea2(o.polygon)) / 2.0;
    if (o.polygon.size() < 3 || area <= s.join_tolerance_m * s.join_tolerance_m) {
      MapIssue issue;
      issue.kind = IssueKind::kDegenerateElement;
      issue.elements = {ElementRef{ElementKind::kObstacle, i}};
      issue.position = o.polygon.empty() ? Vec2::Zero() : o.polygon.front();
      issue.message = "obstacle '" + o.id + "' has no area";
      out.push_back(std::move(issue));
    }
  }
}

MapIssue issueAt(IssueKind kind, Severity severity, std::vector<ElementRef> elements,
                 const Vec2& position, std::string message) {
  MapIssue issue;
  issue.kind = kind;
  issue.severity = severity;
  issue.elements = std::move(elements);
  issue.position = position;
  issue.message = std::move(message);
  return issue;
}

// Ids repeated within markers, lights or nodes (the file format refuses them; an edit may not
// make them, but a map assembled in code can).
template <class T>
void checkDuplicateIds(const std::vector<T>& items, ElementKind kind, const char* what,
                       const std::function<Vec2(const T&)>& where, std::vector<MapIssue>& out) {
  std::map<std::string, std::size_t> first;
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (items[i].id.empty())
      continue;
    const auto [it, fresh] = first.emplace(items[i].id, i);
    if (!fresh)
      out.push_back(issueAt(IssueKind::kDuplicateId, Severity::kError,
                            {ElementRef{kind, it->second}, ElementRef{kind, i}}, where(items[i]),
                            std::string(what) + " id '" + items[i].id + "' is used twice"));
  }
}

void checkCeiling(const WorldMap& map, const ValidationSettings& s, std::vector<MapIssue>& out) {
  checkDuplicateIds<CeilingMarker>(
      map.markers, ElementKind::kMarker, "marker",
      [](const CeilingMarker& m) { return m.position; }, out);
  checkDuplicateIds<CeilingLight>(
      map.lights, ElementKind::kLight, "light",
      [](const CeilingLight& l) { return Vec2((l.tube.a + l.tube.b) / 2.0); }, out);
  // "The map" is what the robot drives in: walls, obstacles and the raster layer.
  Box2 floor;
  for (const Wall& w : map.walls)
    for (const Vec2& p : w.points)
      floor.extend(p);
  for (const Obstacle& o : map.obstacles)
    for (const Vec2& p : o.polygon)
      floor.extend(p);
  if (map.raster && !map.raster->raster.empty())
    floor.extend(map.raster->raster.bounds());
  if (floor.empty())
    return;
  floor.min -= Vec2(s.join_tolerance_m, s.join_tolerance_m);
  floor.max += Vec2(s.join_tolerance_m, s.join_tolerance_m);
  for (std::size_t i = 0; i < map.markers.size(); ++i) {
    const CeilingMarker& m = map.markers[i];
    if (!floor.contains(m.position))
      out.push_back(issueAt(IssueKind::kOutsideMap, Severity::kWarning,
                            {ElementRef{ElementKind::kMarker, i}}, m.position,
                            "marker '" + m.id + "' is outside the map (no robot passes under it)"));
  }
  for (std::size_t i = 0; i < map.lights.size(); ++i) {
    const CeilingLight& l = map.lights[i];
    if (!floor.contains(l.tube.a) || !floor.contains(l.tube.b))
      out.push_back(issueAt(IssueKind::kOutsideMap, Severity::kWarning,
                            {ElementRef{ElementKind::kLight, i}}, (l.tube.a + l.tube.b) / 2.0,
                            "light '" + l.id + "' reaches outside the map"));
  }
  for (std::size_t i = 0; i < map.graph.nodes.size(); ++i) {
    const TopoNode& n = map.graph.nodes[i];
    if (!floor.contains(n.position))
      out.push_back(issueAt(IssueKind::kOutsideMap, Severity::kWarning,
                            {ElementRef{ElementKind::kNode, i}}, n.position,
                            "node '" + n.id + "' is outside the map"));
  }
}

void checkGraph(const WorldMap& map, std::vector<MapIssue>& out) {
  const TopoGraph& g = map.graph;
  checkDuplicateIds<TopoNode>(
      g.nodes, ElementKind::kNode, "node", [](const TopoNode& n) { return n.position; }, out);
  for (std::size_t i = 0; i < g.nodes.size(); ++i) {
    const TopoNode& n = g.nodes[i];
    if (n.marker_id.empty())
      continue;
    const auto m = std::find_if(map.markers.begin(), map.markers.end(),
                                [&](const CeilingMarker& c) { return c.id == n.marker_id; });
    if (m == map.markers.end())
      out.push_back(issueAt(
          IssueKind::kMissingMarker, Severity::kError, {ElementRef{ElementKind::kNode, i}},
          n.position, "node '" + n.id + "' is tied to the missing marker '" + n.marker_id + "'"));
  }
  std::set<std::pair<std::string, std::string>> seen;
  for (std::size_t i = 0; i < g.edges.size(); ++i) {
    const TopoEdge& e = g.edges[i];
    const TopoNode* a = g.node(e.from);
    const TopoNode* b = g.node(e.to);
    const ElementRef self{ElementKind::kEdge, i};
    if (a == nullptr || b == nullptr) {
      const std::string& missing = a == nullptr ? e.from : e.to;
      const TopoNode* other = a == nullptr ? b : a;
      out.push_back(issueAt(
          IssueKind::kMissingNode, Severity::kError, {self}, other ? other->position : Vec2::Zero(),
          "edge '" + e.from + "' - '" + e.to + "' names the missing node '" + missing + "'"));
      continue;
    }
    const Vec2 mid = (a->position + b->position) / 2.0;
    if (e.from == e.to) {
      out.push_back(issueAt(IssueKind::kDegenerateElement, Severity::kError, {self}, mid,
                            "edge '" + e.from + "' joins the node to itself"));
      continue;
    }
    const auto key = std::minmax(e.from, e.to);
    if (!seen.emplace(key.first, key.second).second)
      out.push_back(issueAt(IssueKind::kDuplicateEdge, Severity::kWarning, {self}, mid,
                            "edge '" + e.from + "' - '" + e.to + "' repeats an earlier edge"));
    const double chord = (b->position - a->position).norm();
    if (e.cost_m && *e.cost_m < chord - 1e-9)
      out.push_back(issueAt(IssueKind::kEdgeCostBelowDistance, Severity::kWarning, {self}, mid,
                            "edge '" + e.from + "' - '" + e.to + "' costs " + metres(*e.cost_m) +
                                ", less than the " + metres(chord) +
                                " between its nodes (a corridor is never shorter)"));
  }
}

}  // namespace

std::vector<MapIssue> validateMap(const WorldMap& map, const ValidationSettings& settings) {
  for (double v : {settings.join_tolerance_m, settings.gap_tolerance_m,
                   settings.feature_separation_m, settings.robot_radius_m}) {
    if (!(v >= 0.0) || !std::isfinite(v))
      throw std::invalid_argument("validation tolerances must be finite and >= 0");
  }
  std::vector<MapIssue> out;
  checkOutlines(map, settings, out);
  checkOverlaps(map, settings, out);
  checkStart(map, settings, out);
  checkDegenerate(map, settings, out);
  checkCeiling(map, settings, out);
  checkGraph(map, out);
  return out;
}

}  // namespace irgs::editing
