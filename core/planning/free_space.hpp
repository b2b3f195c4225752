#pragma once
// Free-space tests on a PlanningGrid for path amendment (003_… Fig. 4.7): a segment or a
// triangle is free when every cell it touches is free. World metres in, conservative out: a
// segment through a cell corner counts both cells beside it (grid_line.hpp), and anything
// leaving the grid is not free.

#include <vector>

#include "core/planning/planning_grid.hpp"

namespace irgs {

bool segmentIsFree(const PlanningGrid& grid, const Vec2& a, const Vec2& b);
// Cells whose square meets the triangle: those its edges cross plus those whose centre it
// contains (a square meeting a triangle either is crossed by an edge or lies inside it).
bool triangleIsFree(const PlanningGrid& grid, const Vec2& a, const Vec2& b, const Vec2& c);
// Every leg of the polyline is free.
bool polylineIsFree(const PlanningGrid& grid, const std::vector<Vec2>& points);

}  // namespace irgs
