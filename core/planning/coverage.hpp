#pragma once
// Coverage (cleaning) paths (003_… section 5, Fig. 5.11; digest 4.11): a path that passes every
// reachable part of the free space, either spiralling from the outline inwards as in the thesis
// or in boustrophedon (back-and-forth) lanes.
//
// Method: lanes are lane_cells wide. The inflated grid is sampled at lane centres (a lattice of
// lane_cells x lane_cells blocks, a node where its block's centre cell is free); lattice
// neighbours are joined when the straight segment between their centres is free. The path
// walks unvisited nodes with a preference rule (spiral: straight on, else turn right, so that
// started at the outline it rings inwards clockwise; boustrophedon: along the row, else one
// lane up/down and back), and when no neighbour is unvisited it goes by the shortest lattice
// route to the nearest unvisited node. Coverage counts the free cells reachable from the start
// (8-connected, no corner cutting) that lie within half a lane of the path.

#include <cstddef>
#include <vector>

#include "core/planning/planning_grid.hpp"

namespace irgs {

enum class CoveragePattern { kSpiral, kBoustrophedon };

struct CoverageOptions {
  CoveragePattern pattern = CoveragePattern::kSpiral;
  int lane_cells = 10;  // lane spacing in cells (the robot's cleaning width / resolution)
};

struct CoveragePlan {
  bool ok = false;           // false when the start is outside the grid or blocked
  std::vector<Vec2> points;  // lane-centre waypoints, world metres, consecutive ones free
  std::size_t reachable_cells = 0;
  std::size_t covered_cells = 0;
  double coverage = 0.0;  // covered / reachable, 0..1
  double length_m = 0.0;
  int turns = 0;
  std::size_t jumps = 0;  // routes to the nearest unvisited lane node when boxed in
};

// grid: the inflated planning grid (robot-centre positions). Throws std::invalid_argument when
// lane_cells < 1.
CoveragePlan planCoverage(const PlanningGrid& grid, const Cell& start,
                          const CoverageOptions& options = {});

}  // namespace irgs
