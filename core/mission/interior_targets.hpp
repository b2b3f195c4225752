#pragma once
// Where map building goes next inside the room (003_…, digest 4.5 step 5): on a coarse view of
// the built grid — occupied, free, unknown (free space seen at long range counts as known) —
// inflated by the body radius plus a margin, the nearest reachable cell that is either next to
// unknown space (a frontier) or, inside the outline, within reach of occupied cells that no
// traced loop explains (an unvisited obstacle). The search is core/planning's planToNearest.

#include <optional>
#include <vector>

#include "core/geometry/types.hpp"
#include "core/mapping/occupancy_grid.hpp"
#include "core/mission/explored_record.hpp"

namespace irgs {

struct InteriorTarget {
  Vec2 position = Vec2::Zero();
  bool obstacle = false;  // an unvisited obstacle near `position`, at obstacle_point
  Vec2 obstacle_point = Vec2::Zero();
  std::vector<Vec2> path;  // from the robot's position to `position`, turning points only
};

struct InteriorSearchConfig {
  double cell_m = 0.1;           // coarse cell (a whole number of grid cells)
  double explore_range_m = 3.0;  // 0: the long-range knowledge grid is not used
  double inflate_m = 0.26;       // body radius + clearance margin
  bool beyond_outline = true;    // frontiers anywhere reachable, not only inside the outline
};

// Nothing before the outline is closed, or when no target is reachable.
std::optional<InteriorTarget> chooseInteriorTarget(const Pose2& pose, const OccupancyGrid& grid,
                                                   const OccupancyGrid& explore_grid,
                                                   const ExploredRecord& record,
                                                   const InteriorSearchConfig& config);

}  // namespace irgs
