#include "core/mission/explored_record.hpp"

#include "core/geometry/geometry_queries.hpp"

namespace irgs {

bool ExploredRecord::insideOutline(const Vec2& p) const {
  return outline_ && pointInPolygon(p, outline_->indices);
}

bool ExploredRecord::nearOutline(const Vec2& p, double distance_m) const {
  return outline_ && pointPolygonBoundaryDistance(p, outline_->indices) < distance_m;
}

bool ExploredRecord::explained(const Vec2& p) const {
  if (nearOutline(p, margin_m_))
    return true;
  for (const TracedLoop& loop : obstacles_)
    if (pointInPolygon(p, loop.indices) ||
        pointPolygonBoundaryDistance(p, loop.indices) < margin_m_)
      return true;
  for (const TracedLoop& loop : pockets_)
    if (pointPolygonBoundaryDistance(p, loop.indices) < margin_m_)
      return true;
  return false;
}

bool ExploredRecord::listed(const Vec2& p) const {
  for (const Spot& s : blacklist_)
    if ((p - s.centre).norm() < s.radius_m)
      return true;
  return false;
}

bool ExploredRecord::visitedOften(const Vec2& p) const {
  int loops = 0;
  for (const Vec2& a : anchors_)
    loops += (a - p).norm() < kRevisitRadius_m ? 1 : 0;
  return loops >= kMaxLoopsNearSpot;
}

}  // namespace irgs
