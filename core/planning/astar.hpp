#pragma once
// A* on a PlanningGrid: 8-connected, no corner cutting (a diagonal step needs both orthogonal
// neighbours free), octile heuristic, with a search budget (expansions and/or time from an
// injected clock), a cancel hook and an optional expansion log. Thesis 003_… section 4.1:
// time-capped A* that returns the partial path found so far.
//
// Step costs are integers (kStraightCost per straight step, kDiagonalCost = round(sqrt(2) *
// kStraightCost) per diagonal), so costs compare exactly: ties break deterministically and the
// Dijkstra reference finds the same optimum bit for bit. The octile heuristic on these integer
// costs is the exact obstacle-free distance, hence consistent: the first expansion of a cell is
// optimal and A* returns the optimal cost. PlanResult::cost_m converts to metres (relative
// error of the sqrt(2) rounding: 3e-6).

#include <cstdint>
#include <functional>
#include <optional>
#include <string_view>
#include <vector>

#include "core/planning/planning_grid.hpp"

namespace irgs {

inline constexpr std::uint64_t kStraightCost = 65536;
inline constexpr std::uint64_t kDiagonalCost = 92682;  // round(sqrt(2) * 65536)

// Octile distance between cells in cost units.
inline std::uint64_t octileCost(const Cell& a, const Cell& b) {
  const std::int64_t dc = a.col > b.col ? std::int64_t{a.col} - b.col : std::int64_t{b.col} - a.col;
  const std::int64_t dr = a.row > b.row ? std::int64_t{a.row} - b.row : std::int64_t{b.row} - a.row;
  const auto lo = static_cast<std::uint64_t>(dc < dr ? dc : dr);
  const auto hi = static_cast<std::uint64_t>(dc < dr ? dr : dc);
  return kStraightCost * (hi - lo) + kDiagonalCost * lo;
}

enum class PlanStatus {
  kFound,         // optimal path to the goal
  kPartial,       // budget ran out: path to the expanded cell nearest the goal (least heuristic)
  kNoPath,        // the goal is not reachable from the start
  kStartBlocked,  // start cell blocked (or outside the allowed region)
  kGoalBlocked,   // goal cell blocked (or outside the allowed region)
  kCancelled,     // the cancel hook returned true; no path
  kOutOfBounds,   // start or goal outside the grid (or not finite)
};
std::string_view toString(PlanStatus status);

struct PlanBudget {
  std::uint64_t max_expansions = 0;     // 0 = unlimited
  double max_time_s = 0.0;              // 0 = unlimited; needs now_s
  std::function<double()> now_s;        // injected clock, seconds (core has no clock of its own)
  std::function<bool()> cancelled;      // polled with the clock; true stops with kCancelled
  std::uint32_t check_interval = 1024;  // expansions between clock/cancel polls (>= 1)
};

// How successors are generated. Both return an optimal path with the same cost.
enum class SearchMode {
  // Jump point search (Harabor and Grastien 2011, with the no-corner-cutting rules of their
  // 2014 "Improving Jump Point Search"): straight and diagonal runs are scanned without queueing
  // their cells, only jump points enter the heap. Many times faster on open maps; "expansions"
  // and the expansion log count jump points.
  kJumpPoints,
  // Plain A*: every free neighbour enters the heap (the textbook search of the thesis).
  kPlain,
};

struct AStarOptions {
  SearchMode mode = SearchMode::kJumpPoints;
  PlanBudget budget;
  bool record_expansions = false;  // fill PlanResult::expanded (the frontier, for drawing)
  // Restricts the search to cells with (*region_of_cell)[index] == region (wave points).
  const std::vector<std::int32_t>* region_of_cell = nullptr;
  std::int32_t region = -1;
};

struct PlanResult {
  PlanStatus status = PlanStatus::kNoPath;
  std::vector<Cell> cells;   // start .. goal (or .. best cell for kPartial)
  std::vector<Vec2> points;  // cell centres of `cells`, world metres
  std::uint64_t cost = 0;    // cost units (kStraightCost per straight step)
  double cost_m = 0.0;       // path length, metres
  std::uint64_t expansions = 0;
  std::vector<Cell> expanded;  // expansion order when options.record_expansions

  bool found() const { return status == PlanStatus::kFound; }
};

// A reusable planner: its per-cell arrays live across queries and are invalidated by a
// generation counter instead of being cleared, so a query costs what it expands, not the grid
// size. Not thread-safe; use one planner per thread.
class AStarPlanner {
 public:
  // Throws std::invalid_argument when options.region_of_cell does not match the grid, or
  // budget.max_time_s > 0 without now_s, or a non-finite/negative max_time_s, or
  // check_interval == 0.
  PlanResult plan(const PlanningGrid& grid, const Cell& start, const Cell& goal,
                  const AStarOptions& options = {});
  // World points are mapped to their cells (kOutOfBounds when outside).
  PlanResult plan(const PlanningGrid& grid, const Vec2& start, const Vec2& goal,
                  const AStarOptions& options = {});

 private:
  template <bool kMasked, bool kJump>
  PlanResult search(const PlanningGrid& grid, std::uint32_t start, std::uint32_t goal,
                    const AStarOptions& options);
  void prepare(std::size_t cells);

  struct Entry {
    std::uint64_t f;
    std::uint32_t h;  // heuristic (saturated) for tie-breaking: prefer cells nearer the goal
    std::uint32_t index;
  };
  std::vector<std::uint64_t> g_;
  std::vector<std::uint32_t> parent_;
  std::vector<std::uint32_t> stamp_;  // 2*gen: open this query, 2*gen+1: closed this query
  std::uint32_t generation_ = 0;
  std::vector<Entry> heap_;

  // Jump point scans without a region mask read 8 cells per step from a padded byte copy of
  // the grid (border blocked) and its transpose, built once per grid content: `source` is the
  // grid they were built from (a changed grid is detected by comparison, O(cells) memcmp).
  struct ScanGrids {
    int width = -1, height = -1;
    std::vector<std::uint8_t> source;
    std::vector<std::uint8_t> rows;  // (height + 2) x (width + 2), plus slack, 1 = blocked
    std::vector<std::uint8_t> cols;  // transpose: (width + 2) x (height + 2)
  };
  void prepareScanGrids(const PlanningGrid& grid);
  ScanGrids scan_;
};

// One-shot convenience (allocates a planner).
PlanResult planAStar(const PlanningGrid& grid, const Cell& start, const Cell& goal,
                     const AStarOptions& options = {});

// Plain Dijkstra with the same moves and costs, for tests and benchmarks: no budget, no reuse.
PlanResult dijkstraReference(const PlanningGrid& grid, const Cell& start, const Cell& goal);

// Fills result.points from result.cells and result.cost_m from result.cost.
void finishPlanResult(const PlanningGrid& grid, PlanResult& result);

}  // namespace irgs
