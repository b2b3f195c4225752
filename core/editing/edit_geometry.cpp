#include "core/editing/edit_geometry.hpp"

#include <algorithm>
#include <cmath>

namespace irgs::editing {

double distanceToSegment(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double len2 = ab.squaredNorm();
  if (len2 <= 0.0)
    return (p - a).norm();
  const double t = std::clamp((p - a).dot(ab) / len2, 0.0, 1.0);
  return (p - (a + t * ab)).norm();
}

bool polygonContains(const std::vector<Vec2>& polygon, const Vec2& p) {
  const std::size_t n = polygon.size();
  if (n < 3)
    return false;
  bool inside = false;
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    const Vec2& a = polygon[i];
    const Vec2& b = polygon[j];
    if (distanceToSegment(p, a, b) <= 1e-12)
      return true;
    // Even-odd rule on a ray towards +x.
    if ((a.y() > p.y()) != (b.y() > p.y()) &&
        p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x())
      inside = !inside;
  }
  return inside;
}

double signedArea2(const std::vector<Vec2>& polygon) {
  double sum = 0.0;
  const std::size_t n = polygon.size();
  for (std::size_t i = 0; i < n; ++i)
    sum += cross(polygon[i], polygon[(i + 1) % n]);
  return sum;
}

namespace {

int orientation(const Vec2& a, const Vec2& b, const Vec2& c) {
  const double v = cross(b - a, c - a);
  constexpr double kEps = 1e-12;
  return v > kEps ? 1 : (v < -kEps ? -1 : 0);
}

bool onSegment(const Vec2& a, const Vec2& b, const Vec2& p) {
  return std::min(a.x(), b.x()) - 1e-12 <= p.x() && p.x() <= std::max(a.x(), b.x()) + 1e-12 &&
         std::min(a.y(), b.y()) - 1e-12 <= p.y() && p.y() <= std::max(a.y(), b.y()) + 1e-12;
}

}  // namespace

bool segmentsIntersect(const Vec2& a0, const Vec2& a1, const Vec2& b0, const Vec2& b1) {
  const int o1 = orientation(a0, a1, b0);
  const int o2 = orientation(a0, a1, b1);
  const int o3 = orientation(b0, b1, a0);
  const int o4 = orientation(b0, b1, a1);
  if (o1 != o2 && o3 != o4)
    return true;
  return (o1 == 0 && onSegment(a0, a1, b0)) || (o2 == 0 && onSegment(a0, a1, b1)) ||
         (o3 == 0 && onSegment(b0, b1, a0)) || (o4 == 0 && onSegment(b0, b1, a1));
}

bool polygonsOverlap(const std::vector<Vec2>& a, const std::vector<Vec2>& b) {
  if (a.size() < 3 || b.size() < 3)
    return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    for (std::size_t j = 0; j < b.size(); ++j) {
      if (segmentsIntersect(a[i], a[(i + 1) % a.size()], b[j], b[(j + 1) % b.size()]))
        return true;
    }
  }
  // No edges cross: either one holds the other or they are apart.
  return polygonContains(a, b.front()) || polygonContains(b, a.front());
}

std::size_t wallPieceCount(std::size_t point_count, bool closed) {
  if (point_count < 2)
    return 0;
  return closed && point_count > 2 ? point_count : point_count - 1;
}

}  // namespace irgs::editing
