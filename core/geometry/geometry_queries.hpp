#pragma once
// Small exact-as-floating-point predicates and distances on points, segments and polygons: the
// one place for each of these facts (the simulator's collision, bumper and clearance queries,
// map building's loops, the planners' rasterisation). All inputs in world metres.

#include <span>

#include "core/geometry/types.hpp"

namespace irgs {

// True when the closed segments ab and cd share at least one point (touching counts).
bool segmentsIntersect(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d);

// True when p lies inside the polygon (even-odd rule; points on the boundary may go either way,
// callers test edges separately).
bool pointInPolygon(const Vec2& p, std::span<const Vec2> polygon);

// True when the closed segment ab meets the closed box (Liang–Barsky clipping).
bool segmentIntersectsBox(const Vec2& a, const Vec2& b, const Box2& box);

double pointSegmentDistance(const Vec2& p, const Vec2& a, const Vec2& b);
double segmentSegmentDistance(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d);
double pointBoxDistance(const Vec2& p, const Box2& box);

// True when the polygon (closed, any winding) and the closed segment ab share a point.
bool polygonTouchesSegment(std::span<const Vec2> polygon, const Vec2& a, const Vec2& b);
// True when the polygon and the closed box share a point.
bool polygonTouchesBox(std::span<const Vec2> polygon, const Box2& box);

// The signed area of the polygon (shoelace), > 0 counter-clockwise.
double signedArea(std::span<const Vec2> polygon);
// Distance from p to the closed polygon's boundary (edges, the last back to the first).
double pointPolygonBoundaryDistance(const Vec2& p, std::span<const Vec2> polygon);

// Box around the polygon's vertices.
Box2 boundsOf(std::span<const Vec2> points);

}  // namespace irgs
