#include "core/geometry/geometry_queries.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace irgs {

namespace {

// Sign of the orientation of (a, b, c): > 0 counter-clockwise.
double orient(const Vec2& a, const Vec2& b, const Vec2& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

// c collinear with ab: is it within the bounding box of ab?
bool onSegmentBox(const Vec2& a, const Vec2& b, const Vec2& c) {
  return std::min(a.x(), b.x()) <= c.x() && c.x() <= std::max(a.x(), b.x()) &&
         std::min(a.y(), b.y()) <= c.y() && c.y() <= std::max(a.y(), b.y());
}

}  // namespace

bool segmentsIntersect(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  const double d1 = orient(c, d, a), d2 = orient(c, d, b);
  const double d3 = orient(a, b, c), d4 = orient(a, b, d);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0)))
    return true;
  return (d1 == 0 && onSegmentBox(c, d, a)) || (d2 == 0 && onSegmentBox(c, d, b)) ||
         (d3 == 0 && onSegmentBox(a, b, c)) || (d4 == 0 && onSegmentBox(a, b, d));
}

bool pointInPolygon(const Vec2& p, std::span<const Vec2> polygon) {
  bool inside = false;
  const std::size_t n = polygon.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    const Vec2& pi = polygon[i];
    const Vec2& pj = polygon[j];
    if ((pi.y() > p.y()) != (pj.y() > p.y())) {
      const double x_cross = pj.x() + (p.y() - pj.y()) / (pi.y() - pj.y()) * (pi.x() - pj.x());
      if (p.x() < x_cross)
        inside = !inside;
    }
  }
  return inside;
}

bool segmentIntersectsBox(const Vec2& a, const Vec2& b, const Box2& box) {
  if (box.empty())
    return false;
  double t0 = 0.0, t1 = 1.0;
  const Vec2 d = b - a;
  for (int axis = 0; axis < 2; ++axis) {
    const double lo = box.min[axis], hi = box.max[axis];
    if (d[axis] == 0.0) {
      if (a[axis] < lo || a[axis] > hi)
        return false;
      continue;
    }
    double ta = (lo - a[axis]) / d[axis];
    double tb = (hi - a[axis]) / d[axis];
    if (ta > tb)
      std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
    if (t0 > t1)
      return false;
  }
  return true;
}

double pointSegmentDistance(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).norm();
}

double segmentSegmentDistance(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  if (segmentsIntersect(a, b, c, d))
    return 0.0;
  return std::min({pointSegmentDistance(a, c, d), pointSegmentDistance(b, c, d),
                   pointSegmentDistance(c, a, b), pointSegmentDistance(d, a, b)});
}

double pointBoxDistance(const Vec2& p, const Box2& box) {
  const double dx = std::max({box.min.x() - p.x(), 0.0, p.x() - box.max.x()});
  const double dy = std::max({box.min.y() - p.y(), 0.0, p.y() - box.max.y()});
  return std::hypot(dx, dy);
}

bool polygonTouchesSegment(std::span<const Vec2> polygon, const Vec2& a, const Vec2& b) {
  const std::size_t n = polygon.size();
  if (n == 0)
    return false;
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    if (segmentsIntersect(polygon[j], polygon[i], a, b))
      return true;
  }
  // No edge crossing: the segment is either wholly inside or wholly outside.
  return pointInPolygon(a, polygon);
}

bool polygonTouchesBox(std::span<const Vec2> polygon, const Box2& box) {
  const std::size_t n = polygon.size();
  if (n == 0 || box.empty())
    return false;
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    if (segmentIntersectsBox(polygon[j], polygon[i], box))
      return true;
  }
  // No edge meets the box: the box is wholly inside or wholly outside the polygon.
  return pointInPolygon(0.5 * (box.min + box.max), polygon);
}

double signedArea(std::span<const Vec2> polygon) {
  double twice = 0.0;
  for (std::size_t i = 0; i < polygon.size(); ++i)
    twice += cross(polygon[i], polygon[(i + 1) % polygon.size()]);
  return 0.5 * twice;
}

double pointPolygonBoundaryDistance(const Vec2& p, std::span<const Vec2> polygon) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < polygon.size(); ++i)
    best = std::min(best, pointSegmentDistance(p, polygon[i], polygon[(i + 1) % polygon.size()]));
  return best;
}

Box2 boundsOf(std::span<const Vec2> points) {
  Box2 box;
  for (const Vec2& p : points)
    box.extend(p);
  return box;
}

}  // namespace irgs
