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
// User wave points: planThroughWavePoints visits given cells in order (e.g. doorways).

#include <cstdint>
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
  int block_cells = 0;
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
