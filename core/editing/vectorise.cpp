#include "core/editing/vectorise.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <unordered_map>

namespace irgs::editing {

namespace {

// A corner of the cell grid: (i, j) is at origin + (i, j) * resolution.
struct Corner {
  int i = 0;
  int j = 0;
  friend bool operator==(const Corner&, const Corner&) = default;
};

struct EdgeList {
  std::array<int, 2> to_edge{-1, -1};  // outgoing edge indices (at most two: a saddle)
};

struct DirectedEdge {
  Corner from;
  Corner to;
  bool used = false;
};

std::int64_t key(const Corner& c, int width) {
  return static_cast<std::int64_t>(c.j) * (static_cast<std::int64_t>(width) + 1) + c.i;
}

int cross(const Corner& a, const Corner& b, const Corner& c) {  // (b - a) x (c - b)
  return (b.i - a.i) * (c.j - b.j) - (b.j - a.j) * (c.i - b.i);
}

double pointSegmentDistance(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 d = b - a;
  const double len2 = d.squaredNorm();
  if (len2 <= 0.0)
    return (p - a).norm();
  const double t = std::clamp((p - a).dot(d) / len2, 0.0, 1.0);
  return (p - (a + t * d)).norm();
}

// Ramer-Douglas-Peucker on an open polyline, keeping both ends.
void simplify(const std::vector<Vec2>& in, std::size_t first, std::size_t last, double tolerance,
              std::vector<bool>& keep) {
  if (last <= first + 1)
    return;
  double worst = -1.0;
  std::size_t worst_i = first;
  for (std::size_t i = first + 1; i < last; ++i) {
    const double d = pointSegmentDistance(in[i], in[first], in[last]);
    if (d > worst) {
      worst = d;
      worst_i = i;
    }
  }
  if (worst <= tolerance)
    return;
  keep[worst_i] = true;
  simplify(in, first, worst_i, tolerance, keep);
  simplify(in, worst_i, last, tolerance, keep);
}

// A closed loop simplified: split at the first point and the point farthest from it.
std::vector<Vec2> simplifyLoop(const std::vector<Vec2>& loop, double tolerance) {
  if (loop.size() <= 4)
    return loop;
  std::size_t far = 0;
  double far_d = -1.0;
  for (std::size_t i = 1; i < loop.size(); ++i) {
    const double d = (loop[i] - loop[0]).norm();
    if (d > far_d) {
      far_d = d;
      far = i;
    }
  }
  std::vector<Vec2> ring = loop;
  ring.push_back(loop[0]);  // close it for the second half
  std::vector<bool> keep(ring.size(), false);
  keep[0] = keep[far] = keep[ring.size() - 1] = true;
  simplify(ring, 0, far, tolerance, keep);
  simplify(ring, far, ring.size() - 1, tolerance, keep);
  std::vector<Vec2> out;
  for (std::size_t i = 0; i + 1 < ring.size(); ++i)
    if (keep[i])
      out.push_back(ring[i]);
  return out;
}

}  // namespace

std::vector<std::vector<Vec2>> traceOccupiedOutlines(const RasterMap& raster,
                                                     const VectoriseSettings& settings) {
  if (raster.width < 0 || raster.height < 0 ||
      raster.cells.size() !=
          static_cast<std::size_t>(raster.width) * static_cast<std::size_t>(raster.height))
    throw std::invalid_argument("traceOccupiedOutlines: cell count does not match the size");
  if (!(std::isfinite(raster.resolution_m) && raster.resolution_m > 0.0))
    throw std::invalid_argument("traceOccupiedOutlines: resolution must be > 0");
  if (!(settings.tolerance_m >= 0.0) || !(settings.min_size_m >= 0.0))
    throw std::invalid_argument("traceOccupiedOutlines: tolerance and size must be >= 0");
  const double res = raster.resolution_m;
  const double tolerance = settings.tolerance_m > 0.0 ? settings.tolerance_m : res;
  const double min_size = settings.min_size_m > 0.0 ? settings.min_size_m : 3.0 * res;
  const auto occupied = [&](int c, int r) {
    return raster.inside(c, r) && raster.at(c, r) >= settings.occupied_threshold;
  };

  std::vector<DirectedEdge> edges;
  std::unordered_map<std::int64_t, EdgeList> outgoing;
  const auto add = [&](Corner from, Corner to) {
    EdgeList& list = outgoing[key(from, raster.width)];
    list.to_edge[list.to_edge[0] < 0 ? 0 : 1] = static_cast<int>(edges.size());
    edges.push_back({from, to});
  };
  for (int r = 0; r < raster.height; ++r)
    for (int c = 0; c < raster.width; ++c) {
      if (!occupied(c, r))
        continue;
      if (!occupied(c, r - 1))
        add({c, r}, {c + 1, r});  // bottom, moving +x
      if (!occupied(c + 1, r))
        add({c + 1, r}, {c + 1, r + 1});  // right, moving +y
      if (!occupied(c, r + 1))
        add({c + 1, r + 1}, {c, r + 1});  // top, moving -x
      if (!occupied(c - 1, r))
        add({c, r + 1}, {c, r});  // left, moving -y
    }

  std::vector<std::vector<Vec2>> outlines;
  for (std::size_t e0 = 0; e0 < edges.size(); ++e0) {
    if (edges[e0].used)
      continue;
    std::vector<Corner> corners;
    std::size_t e = e0;
    const Corner start = edges[e0].from;
    while (true) {
      edges[e].used = true;
      corners.push_back(edges[e].from);
      const Corner at = edges[e].to;
      if (at == start)
        break;
      const EdgeList& list = outgoing[key(at, raster.width)];
      int next = -1;
      for (int candidate : list.to_edge) {
        if (candidate < 0 || edges[static_cast<std::size_t>(candidate)].used)
          continue;
        // At a saddle take the left turn (keeps diagonal neighbours apart).
        if (next < 0 || cross(edges[e].from, at, edges[static_cast<std::size_t>(candidate)].to) >
                            cross(edges[e].from, at, edges[static_cast<std::size_t>(next)].to))
          next = candidate;
      }
      if (next < 0)
        break;  // cannot happen for a consistent border; end the loop rather than spin
      e = static_cast<std::size_t>(next);
    }
    // Merge collinear runs: keep corners where the direction changes.
    std::vector<Vec2> points;
    const std::size_t n = corners.size();
    for (std::size_t k = 0; k < n; ++k) {
      const Corner& prev = corners[(k + n - 1) % n];
      const Corner& here = corners[k];
      const Corner& next = corners[(k + 1) % n];
      if (cross(prev, here, next) != 0)
        points.push_back({raster.origin.x + here.i * res, raster.origin.y + here.j * res});
    }
    if (points.size() < 3)
      continue;
    Box2 box;
    for (const Vec2& p : points)
      box.extend(p);
    if ((box.max - box.min).norm() < min_size)
      continue;
    std::vector<Vec2> simplified = simplifyLoop(points, tolerance);
    if (simplified.size() >= 3)
      outlines.push_back(std::move(simplified));
  }
  return outlines;
}

Edit vectoriseRaster(const WorldMap& map, const VectoriseSettings& settings) {
  Edit edit;
  edit.label = "Vectorise raster";
  if (!map.raster || map.raster->raster.empty())
    return edit;
  // The ids and indices the new walls get; the raster itself is not copied.
  WorldMap scratch;
  scratch.walls = map.walls;
  scratch.obstacles = map.obstacles;
  scratch.features = map.features;
  for (std::vector<Vec2>& outline : traceOccupiedOutlines(map.raster->raster, settings)) {
    Wall wall;
    wall.id = uniqueId(scratch, "raster");
    wall.points = std::move(outline);
    wall.closed = true;
    Edit one = addElement(scratch, wall);
    applyEdit(scratch, one);
    for (Change& change : one.changes)
      edit.changes.push_back(std::move(change));
    edit.selection_after.push_back({ElementKind::kWall, scratch.walls.size() - 1});
  }
  return edit;
}

}  // namespace irgs::editing
