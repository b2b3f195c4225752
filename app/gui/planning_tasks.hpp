#pragma once
// The planning work behind the GUI's goal and coverage modes, as plain functions on core types
// (no Qt), so it is tested without a window: planning grids from the loaded map or a sonar
// grid, the goal preview (raw A* path beside the amended one, with turns, length and the
// turn-aware time of path_amendment.hpp), coverage over a chosen rectangle, and the live
// coverage of that rectangle by the robot's body (CoverageSweep).

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/mapping/occupancy_grid.hpp"
#include "core/planning/astar.hpp"
#include "core/planning/coverage.hpp"
#include "core/planning/path_amendment.hpp"
#include "core/planning/planning_grid.hpp"
#include "core/planning/traveling.hpp"
#include "core/world/world_map.hpp"

namespace irgs::gui {

struct PlanningSettings {
  double resolution_m = 0.05;
  double clearance_m = 0.03;  // kept between the robot's body and obstacles, beyond its radius
  double turn_quantum_rad = degToRad(15.0);
  TravelTimeModel time_model;  // the speeds the robot drives at (the SEGMENTS primitive's)
  double budget_s = 0.25;      // A* wall-time budget: the GUI never waits longer for a preview
  std::uint64_t max_expansions = 0;
  double goal_snap_m = 0.25;  // a goal this close to a free cell moves onto it
};

// The grid the planners use (robot centre positions: inflated by body radius + clearance) and
// the same area uninflated (for coverage accounting). Either may be empty when the source is.
struct PlanningGrids {
  PlanningGrid inflated;
  PlanningGrid raw;
  std::string source;  // "map" or "sonar grid", for messages
};
// Throws std::invalid_argument for invalid settings or maps the builders reject.
PlanningGrids gridsFromWorld(const WorldMap& map, double body_radius_m,
                             const PlanningSettings& settings);
PlanningGrids gridsFromOccupancy(const OccupancyGrid& grid, double body_radius_m,
                                 const PlanningSettings& settings, const std::string& name);

struct GoalPreview {
  bool ok = false;    // a path to drive exists (kFound, or kPartial to the best cell)
  std::string error;  // why not, or a note (goal moved, budget ran out)
  PlanStatus status = PlanStatus::kNoPath;
  Vec2 goal = Vec2::Zero();   // the goal driven to (snapped onto a free cell when needed)
  std::vector<Vec2> raw;      // A* path, turning points only, world metres
  std::vector<Vec2> amended;  // amended path (what is driven), starting at the robot
  int raw_turns = 0, amended_turns = 0;
  double raw_length_m = 0.0, amended_length_m = 0.0;
  double raw_time_s = 0.0, amended_time_s = 0.0;  // turn-aware travel time, from the pose
  std::uint64_t expansions = 0;
  double planning_time_s = 0.0;
  TravelPlan travel;  // amended path as turn + distance segments from the robot heading
};

// Plans from the robot pose to the goal on grids.inflated. `cancelled` (may be empty) is polled
// during the search; `now_s` (may be empty: no time budget) is a monotonic clock in seconds.
GoalPreview previewGoal(const PlanningGrids& grids, const Pose2& robot, const Vec2& goal,
                        const PlanningSettings& settings, const std::function<double()>& now_s,
                        const std::function<bool()>& cancelled = {});

struct CoveragePreview {
  bool ok = false;
  std::string error;
  Box2 region;                 // the rectangle as clipped to the grid
  std::vector<Vec2> approach;  // robot -> start of the coverage path (amended A*)
  CoveragePlan coverage;       // on the region's part of the inflated grid
  std::vector<Vec2> path;      // approach + coverage: what is driven
  TravelPlan travel;
  double time_s = 0.0;           // turn-aware estimate of the whole path
  PlanningGrid region_inflated;  // the cropped grids, for CoverageSweep
  PlanningGrid region_raw;
  Cell region_start;
};

// Coverage of the cells of `region` (world rectangle) with lanes lane_m apart.
CoveragePreview previewCoverage(const PlanningGrids& grids, const Pose2& robot, const Box2& region,
                                CoveragePattern pattern, double lane_m,
                                const PlanningSettings& settings,
                                const std::function<double()>& now_s);

// The part of `grid` whose cell centres lie inside `box` (same resolution and cell alignment),
// or an empty grid when the box misses it.
PlanningGrid cropGrid(const PlanningGrid& grid, const Box2& box);

// Which cells of a region the robot's body has passed over. "Sweepable" cells are the free
// cells (uninflated) within the body radius of a robot-centre cell (inflated grid) reachable
// from the start: the most any path could sweep. Coverage = swept sweepable / sweepable.
class CoverageSweep {
 public:
  CoverageSweep() = default;
  // region_raw and region_inflated must have the same geometry (throws std::invalid_argument).
  CoverageSweep(PlanningGrid region_raw, const PlanningGrid& region_inflated, const Cell& start,
                double body_radius_m);
  // Marks the cells under a body centred at p (world metres); non-finite points are ignored.
  void addPosition(const Vec2& p);
  double coverage() const;
  std::size_t sweepableCells() const { return sweepable_count_; }
  std::size_t sweptCells() const { return swept_count_; }
  bool empty() const { return sweepable_count_ == 0; }

 private:
  PlanningGrid raw_;
  std::vector<std::uint8_t> state_;  // 0 = not sweepable, 1 = sweepable, 2 = swept
  std::vector<Cell> disc_;           // cell offsets within the body radius
  std::size_t sweepable_count_ = 0;
  std::size_t swept_count_ = 0;
};

}  // namespace irgs::gui
