#pragma once
// Wave points (003_… section 4.1, digest 4.8): the map is partitioned into sub-maps (regions)
// joined by entrances; A* runs inside one region at a time between wave points, which shrinks
// each search, and the sub-paths are joined at the wave points.
//
// Automatic partition: square blocks of block_cells x block_cells cells; a region is a
// 4-connected component of free cells inside one block (8-connected moves without corner
// cutting connect exactly the same cells). Where two regions touch across a block border, each
// maximal run of touching cell pairs is one entrance, its wave point the middle pair. Every
// crossing belongs to a run, so regions joined in the grid are joined in the region graph: a
// path exists through wave points whenever one exists at all. Costs between the wave points of
// a region are exact (A* confined to the region), so the region-level route is the best route
// through wave points, not necessarily the grid optimum.
//
// Doorway partition: detectDoorways finds narrow passages (doorways) on the UNINFLATED grid and
// partitionAtDoorways cuts the free space along their door lines, so regions are rooms and the
// wave points are the doorways, as a person would partition a flat.
//
// User wave points: planThroughWavePoints visits given cells in order (e.g. doorways).

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/planning/astar.hpp"

namespace irgs {

struct Entrance {
  std::int32_t region_a = -1;
  std::int32_t region_b = -1;
  Cell a;  // wave point cell on region_a's side
  Cell b;  // 4-neighbour of a on region_b's side
};

struct WaveRegions {
  int block_cells = 0;                       // 0 for a doorway partition
  std::vector<std::int32_t> region_of_cell;  // -1 for blocked cells
  std::int32_t region_count = 0;
  std::vector<Entrance> entrances;
  // Exact cost (cost units) between the entrance end points of each region:
  // links[k] = {node_u, node_v, cost}, nodes numbered 2*entrance (a) and 2*entrance+1 (b).
  struct Link {
    std::uint32_t u, v;
    std::uint64_t cost;
  };
  std::vector<Link> links;
  std::uint64_t build_expansions = 0;
};

// Throws std::invalid_argument when block_cells < 2.
WaveRegions partitionIntoBlocks(const PlanningGrid& grid, int block_cells);

struct WavePlan {
  PlanStatus status = PlanStatus::kNoPath;
  std::vector<Cell> cells;
  std::vector<Vec2> points;
  std::vector<std::size_t> wave_indices;  // indices into cells/points of the wave points passed
  std::uint64_t cost = 0;
  double cost_m = 0.0;
  std::uint64_t expansions = 0;  // summed over the region searches of this query

  bool found() const { return status == PlanStatus::kFound; }
};

// A narrow passage between two obstacles: its door line runs from jamb_a to jamb_b (the first
// blocked cells on either side, measured between cell boundaries), the wave point is the free
// cell in its middle.
struct Doorway {
  Cell cell;                   // wave point: the free cell at the middle of the door line
  Vec2 centre = Vec2::Zero();  // world position of that cell's centre
  double width_m = 0.0;        // free width along the door line
  double direction_rad = 0.0;  // direction of the door line (jamb_a -> jamb_b), [0, pi)
  Vec2 jamb_a = Vec2::Zero();  // ends of the free part of the door line
  Vec2 jamb_b = Vec2::Zero();
};

struct DoorwayOptions {
  // A passage is a doorway when its width is in [min_width_m, max_width_m]: narrower than a
  // door the robot does not fit (use the robot's diameter), wider is an opening between spaces.
  double min_width_m = 0.3;
  double max_width_m = 1.2;
  // Both sides of the door must open up: within depth_m of the door line, perpendicular to it,
  // the clearance must grow to at least open_ratio x half the door width (a long corridor of
  // constant width is no doorway).
  double depth_m = 1.2;
  double open_ratio = 1.2;
  // Door lines are searched in this many directions over 180 deg.
  int directions = 24;
};

// What is wrong with the options (non-finite, min > max, min <= 0, ratio <= 1, fewer than 4
// directions), or nothing.
std::optional<std::string> doorwayOptionsError(const DoorwayOptions& options);

// Doorways of `grid` (use the grid BEFORE inflation: widths are between the obstacles). Method:
// the exact distance transform gives each free cell's clearance; cells on the medial axis
// (clearance not smaller than both neighbours along some axis) whose clearance puts the
// passage width in range are candidates; a candidate's door line is the shortest free chord
// through it over `directions` directions; it is a doorway when that chord is within the width
// range and the space opens up on both sides (depth_m, open_ratio). Candidates of one passage
// (8-connected) give one doorway: the one with the narrowest chord; a doorway whose centre lies
// within half a width of a narrower one's door line is the same passage and dropped.
// Deterministic; ordered by row, then column. Throws std::invalid_argument for invalid options.
std::vector<Doorway> detectDoorways(const PlanningGrid& grid, const DoorwayOptions& options = {});

// Regions split at the doorways: each door line (from jamb to jamb, 4-connected cells) is cut,
// the free cells are grouped into 4-connected regions, and the cut cells join the region on
// their left (the side of +normal, normal = door direction rotated +90 deg). Each doorway
// joining two different regions is one entrance (its wave point on one side, its 4-neighbour
// across the line on the other); a "doorway" that does not separate anything (a gap between
// a free-standing obstacle and a wall) adds no entrance. `grid` is the planning grid (usually
// inflated); the doorways come from detectDoorways on the same grid before inflation (same
// size and origin: cells are taken as they are; throws std::invalid_argument for a doorway cell
// outside the grid). A door the inflated robot does not fit through (its wave point blocked)
// adds no entrance. The result works with planWithWavePoints; block_cells is 0.
WaveRegions partitionAtDoorways(const PlanningGrid& grid, const std::vector<Doorway>& doorways);

// Plans start -> goal region by region. regions must come from partitionIntoBlocks on the same
// grid (throws std::invalid_argument when its size differs). options' budget and cancel hook
// apply to each region search; a partial region search ends the query with kPartial and the
// path so far. options.region_of_cell must be null.
WavePlan planWithWavePoints(const PlanningGrid& grid, const WaveRegions& regions, const Cell& start,
                            const Cell& goal, const AStarOptions& options = {});

// Plans start -> wave_points[0] -> ... -> goal with one A* per leg; a blocked or unreachable
// wave point gives that leg's status.
WavePlan planThroughWavePoints(const PlanningGrid& grid, const Cell& start, const Cell& goal,
                               const std::vector<Cell>& wave_points,
                               const AStarOptions& options = {});

}  // namespace irgs
