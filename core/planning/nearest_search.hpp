#pragma once
// Dijkstra from a start cell to the nearest free cell that passes a goal test, with the A*
// planner's moves and integer costs (8-connected, no corner cutting, astar.hpp): "where is the
// closest reachable cell of this kind, and the way there" (map building's interior targets:
// frontiers and unvisited obstacles). The reference Dijkstra of astar.hpp is this search with
// a one-cell goal.

#include <functional>

#include "core/planning/astar.hpp"
#include "core/planning/planning_grid.hpp"

namespace irgs {

using GoalTest = std::function<bool(const Cell& cell)>;

// The cheapest path from `start` to a free cell for which is_goal holds, cells settled in cost
// order (ties in index order, deterministic). The start cell counts only when
// start_may_be_goal. kOutOfBounds / kStartBlocked for a bad start, kNoPath when no reachable
// cell passes.
PlanResult planToNearest(const PlanningGrid& grid, const Cell& start, const GoalTest& is_goal,
                         bool start_may_be_goal = false);

}  // namespace irgs
