#pragma once
// Small plane-geometry helpers the editor needs (distances, polygon tests, segment crossings).
// World metres throughout.

#include <cstddef>
#include <vector>

#include "core/geometry/types.hpp"

namespace irgs::editing {

// Distance from p to the closed segment a-b (a point when a == b).
double distanceToSegment(const Vec2& p, const Vec2& a, const Vec2& b);

// Whether p is inside the polygon (boundary included; either winding). Fewer than three
// vertices contain nothing.
bool polygonContains(const std::vector<Vec2>& polygon, const Vec2& p);

// Twice the signed area of the polygon: > 0 for counter-clockwise vertices.
double signedArea2(const std::vector<Vec2>& polygon);

// Whether the closed segments a0-a1 and b0-b1 share a point (touching counts).
bool segmentsIntersect(const Vec2& a0, const Vec2& a1, const Vec2& b0, const Vec2& b1);

// Whether the interiors or boundaries of two polygons share a point.
bool polygonsOverlap(const std::vector<Vec2>& a, const std::vector<Vec2>& b);

// Pieces of a wall polyline: (points[i], points[i+1]), plus the closing piece when closed.
std::size_t wallPieceCount(std::size_t point_count, bool closed);

}  // namespace irgs::editing
