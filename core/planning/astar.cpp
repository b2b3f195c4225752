#include "core/planning/astar.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <queue>
#include <stdexcept>

#include "core/planning/nearest_search.hpp"

namespace irgs {
namespace {

constexpr std::uint32_t kNoParent = std::numeric_limits<std::uint32_t>::max();

// Min-heap order on (f, h): among equal f, prefer the smaller heuristic (larger g), which keeps
// the search on one of the many equal-cost 8-connected paths instead of flooding the plateau.
template <class E>
struct Later {
  bool operator()(const E& a, const E& b) const { return a.f != b.f ? a.f > b.f : a.h > b.h; }
};

std::uint32_t saturate32(std::uint64_t v) {
  return v > std::numeric_limits<std::uint32_t>::max() ? std::numeric_limits<std::uint32_t>::max()
                                                       : static_cast<std::uint32_t>(v);
}

// Status before any search, or nothing when start and goal are usable.
std::optional<PlanStatus> precheck(const PlanningGrid& grid, const Cell& start, const Cell& goal,
                                   const std::vector<std::int32_t>* region, std::int32_t id) {
  if (!grid.inside(start) || !grid.inside(goal))
    return PlanStatus::kOutOfBounds;
  const auto allowed = [&](const Cell& c) {
    return grid.isFree(c) && (region == nullptr || (*region)[grid.index(c)] == id);
  };
  if (!allowed(start))
    return PlanStatus::kStartBlocked;
  if (!allowed(goal))
    return PlanStatus::kGoalBlocked;
  return std::nullopt;
}

// Slack bytes before and after the padded scan grids so that 8-byte loads at the border stay in
// the buffer.
constexpr std::size_t kSlack = 16;
constexpr std::uint64_t kLanes = 0x0101010101010101ULL;

std::uint64_t load8(const std::uint8_t* p) {
  std::uint64_t v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

// Straight jump scan along a row of a padded byte grid (1 = blocked, border blocked), 8 cells per
// step (byte lanes, little-endian). Starts at x (padded), moving dir = +1 or -1. Returns the
// first jump point's x, or -1 when the scan runs into a blocked cell first. A jump point is
// goal_x (when the goal lies on this row, else pass -1) or a cell with a forced neighbour: a free
// cell beside it (row y +- 1) whose cell one step behind is blocked.
int scanRun(const std::uint8_t* base, std::size_t stride, int x, int y, int dir, int goal_x) {
  static_assert(std::endian::native == std::endian::little, "byte lanes assume little-endian");
  const std::uint8_t* row = base + static_cast<std::size_t>(y) * stride;
  const std::uint8_t* up = row + stride;
  const std::uint8_t* down = row - stride;
  if (dir > 0) {
    for (;; x += 8) {
      const std::uint64_t b = load8(row + x);
      const std::uint64_t m =
          (b | (~load8(up + x) & load8(up + x - 1)) | (~load8(down + x) & load8(down + x - 1))) &
          kLanes;
      const int k = m != 0 ? std::countr_zero(m) >> 3 : 8;
      if (goal_x >= x && goal_x - x <= k && goal_x - x < 8)
        return goal_x;
      if (k < 8)
        return ((b >> (8 * k)) & 1) != 0 ? -1 : x + k;
    }
  }
  for (;; x -= 8) {
    const int lo = x - 7;  // lane j holds cell lo + j; the cell behind (moving -x) is lo + j + 1
    const std::uint64_t b = load8(row + lo);
    const std::uint64_t m =
        (b | (~load8(up + lo) & load8(up + lo + 1)) | (~load8(down + lo) & load8(down + lo + 1))) &
        kLanes;
    const int k = m != 0 ? (63 - std::countl_zero(m)) >> 3 : -1;
    if (goal_x <= x && goal_x >= lo + k && goal_x >= lo)
      return goal_x;
    if (k >= 0)
      return ((b >> (8 * k)) & 1) != 0 ? -1 : lo + k;
  }
}

}  // namespace

void AStarPlanner::prepareScanGrids(const PlanningGrid& grid) {
  if (scan_.width == grid.width && scan_.height == grid.height && scan_.source == grid.blocked)
    return;
  const auto w = static_cast<std::size_t>(grid.width), h = static_cast<std::size_t>(grid.height);
  scan_.width = grid.width;
  scan_.height = grid.height;
  scan_.source = grid.blocked;
  scan_.rows.assign((w + 2) * (h + 2) + 2 * kSlack, 1);
  scan_.cols.assign((w + 2) * (h + 2) + 2 * kSlack, 1);
  std::uint8_t* rows = scan_.rows.data() + kSlack;
  std::uint8_t* cols = scan_.cols.data() + kSlack;
  for (std::size_t r = 0; r < h; ++r)
    for (std::size_t c = 0; c < w; ++c) {
      const std::uint8_t v = grid.blocked[r * w + c] != 0 ? 1 : 0;
      rows[(r + 1) * (w + 2) + c + 1] = v;
      cols[(c + 1) * (h + 2) + r + 1] = v;
    }
}

std::string_view toString(PlanStatus status) {
  switch (status) {
    case PlanStatus::kFound:
      return "found";
    case PlanStatus::kPartial:
      return "partial";
    case PlanStatus::kNoPath:
      return "no path";
    case PlanStatus::kStartBlocked:
      return "start blocked";
    case PlanStatus::kGoalBlocked:
      return "goal blocked";
    case PlanStatus::kCancelled:
      return "cancelled";
    case PlanStatus::kOutOfBounds:
      return "out of bounds";
  }
  return "unknown";
}

void finishPlanResult(const PlanningGrid& grid, PlanResult& result) {
  result.points.clear();
  result.points.reserve(result.cells.size());
  for (const Cell& c : result.cells)
    result.points.push_back(grid.cellCentre(c));
  result.cost_m =
      static_cast<double>(result.cost) / static_cast<double>(kStraightCost) * grid.resolution_m;
}

void AStarPlanner::prepare(std::size_t cells) {
  if (stamp_.size() != cells) {
    g_.assign(cells, 0);
    parent_.assign(cells, kNoParent);
    stamp_.assign(cells, 0);
    generation_ = 0;
  }
  // Stamps 2*gen and 2*gen+1 must not collide with older ones: on wrap-around clear once.
  if (generation_ >= (std::numeric_limits<std::uint32_t>::max() >> 1) - 1) {
    std::fill(stamp_.begin(), stamp_.end(), 0);
    generation_ = 0;
  }
  ++generation_;
  heap_.clear();
}

PlanResult AStarPlanner::plan(const PlanningGrid& grid, const Vec2& start, const Vec2& goal,
                              const AStarOptions& options) {
  const auto s = grid.worldToCell(start);
  const auto g = grid.worldToCell(goal);
  if (!s || !g) {
    PlanResult r;
    r.status = PlanStatus::kOutOfBounds;
    return r;
  }
  return plan(grid, *s, *g, options);
}

PlanResult AStarPlanner::plan(const PlanningGrid& grid, const Cell& start, const Cell& goal,
                              const AStarOptions& options) {
  const PlanBudget& b = options.budget;
  if (options.region_of_cell != nullptr && options.region_of_cell->size() != grid.cellCount())
    throw std::invalid_argument("AStarPlanner: region_of_cell does not match the grid");
  if (!std::isfinite(b.max_time_s) || b.max_time_s < 0.0)
    throw std::invalid_argument("AStarPlanner: max_time_s must be finite and >= 0");
  if (b.max_time_s > 0.0 && !b.now_s)
    throw std::invalid_argument("AStarPlanner: max_time_s needs a clock (now_s)");
  if (b.check_interval == 0)
    throw std::invalid_argument("AStarPlanner: check_interval must be >= 1");
  if (grid.blocked.size() != grid.cellCount())
    throw std::invalid_argument("AStarPlanner: grid cells do not match its size");
  PlanResult result;
  if (const auto status = precheck(grid, start, goal, options.region_of_cell, options.region)) {
    result.status = *status;
    return result;
  }
  if (b.cancelled && b.cancelled()) {
    result.status = PlanStatus::kCancelled;
    return result;
  }
  const auto s = static_cast<std::uint32_t>(grid.index(start));
  const auto g = static_cast<std::uint32_t>(grid.index(goal));
  const bool masked = options.region_of_cell != nullptr;
  if (!masked && options.mode == SearchMode::kJumpPoints)
    prepareScanGrids(grid);
  if (options.mode == SearchMode::kJumpPoints)
    return masked ? search<true, true>(grid, s, g, options)
                  : search<false, true>(grid, s, g, options);
  return masked ? search<true, false>(grid, s, g, options)
                : search<false, false>(grid, s, g, options);
}

template <bool kMasked, bool kJump>
PlanResult AStarPlanner::search(const PlanningGrid& grid, std::uint32_t start, std::uint32_t goal,
                                const AStarOptions& options) {
  prepare(grid.cellCount());
  const std::uint32_t open = 2 * generation_, closed = open + 1;
  const std::uint8_t* blocked = grid.blocked.data();
  const std::int32_t* region = kMasked ? options.region_of_cell->data() : nullptr;
  const std::int32_t region_id = options.region;
  const int w = grid.width, h = grid.height;
  const auto uw = static_cast<std::uint32_t>(w);
  const Cell goal_cell = grid.cellOf(goal);
  const PlanBudget& budget = options.budget;
  const bool timed = budget.max_time_s > 0.0;
  const double t0 = timed ? budget.now_s() : 0.0;
  const bool polling = timed || static_cast<bool>(budget.cancelled);
  const auto free_at = [&](std::uint32_t i) {
    if constexpr (kMasked)
      return blocked[i] == 0 && region[i] == region_id;
    else
      return blocked[i] == 0;
  };
  const auto heuristic = [&](int col, int row) { return octileCost({col, row}, goal_cell); };
  // Free and inside the grid (JPS scans walk up to the border).
  const auto open_at = [&](int col, int row) {
    return col >= 0 && row >= 0 && col < w && row < h &&
           free_at(static_cast<std::uint32_t>(row) * uw + static_cast<std::uint32_t>(col));
  };
  // Straight scan from (col, row) (already one step along (dc, dr)): the first jump point, or
  // nothing. A cell is a jump point when it is the goal or has a forced neighbour: a free side
  // cell whose cell behind is blocked, so the only optimal way there leads through this cell.
  const std::uint8_t* scan_rows = kMasked || !kJump ? nullptr : scan_.rows.data() + kSlack;
  const std::uint8_t* scan_cols = kMasked || !kJump ? nullptr : scan_.cols.data() + kSlack;
  const auto jump_straight = [&](int col, int row, int dc, int dr) -> std::optional<Cell> {
    if constexpr (!kMasked) {
      if (dr == 0) {
        const int x = scanRun(scan_rows, uw + 2, col + 1, row + 1, dc,
                              row == goal_cell.row ? goal_cell.col + 1 : -1);
        return x < 0 ? std::nullopt : std::optional<Cell>(Cell{x - 1, row});
      }
      const int y = scanRun(scan_cols, static_cast<std::size_t>(h) + 2, row + 1, col + 1, dr,
                            col == goal_cell.col ? goal_cell.row + 1 : -1);
      return y < 0 ? std::nullopt : std::optional<Cell>(Cell{col, y - 1});
    }
    for (;;) {
      if (!open_at(col, row))
        return std::nullopt;
      if (col == goal_cell.col && row == goal_cell.row)
        return Cell{col, row};
      if (dc != 0) {
        if ((open_at(col, row + 1) && !open_at(col - dc, row + 1)) ||
            (open_at(col, row - 1) && !open_at(col - dc, row - 1)))
          return Cell{col, row};
      } else {
        if ((open_at(col + 1, row) && !open_at(col + 1, row - dr)) ||
            (open_at(col - 1, row) && !open_at(col - 1, row - dr)))
          return Cell{col, row};
      }
      col += dc;
      row += dr;
    }
  };
  // Diagonal scan: a cell is a jump point when it is the goal or a straight scan from it along
  // either component finds one. The diagonal step needs both orthogonal cells free.
  const auto jump_diagonal = [&](int col, int row, int dc, int dr) -> std::optional<Cell> {
    for (;;) {
      if (!open_at(col, row))
        return std::nullopt;
      if (col == goal_cell.col && row == goal_cell.row)
        return Cell{col, row};
      if (jump_straight(col + dc, row, dc, 0) || jump_straight(col, row + dr, 0, dr))
        return Cell{col, row};
      if (!open_at(col + dc, row) || !open_at(col, row + dr))
        return std::nullopt;
      col += dc;
      row += dr;
    }
  };

  PlanResult result;
  std::uint64_t* gs = g_.data();
  std::uint32_t* parent = parent_.data();
  std::uint32_t* stamp = stamp_.data();
  const Later<Entry> later;

  gs[start] = 0;
  parent[start] = kNoParent;
  stamp[start] = open;
  const Cell sc = grid.cellOf(start);
  const std::uint64_t h_start = heuristic(sc.col, sc.row);
  heap_.push_back({h_start, saturate32(h_start), start});
  std::uint32_t best = start;
  std::uint64_t best_h = h_start;
  std::uint64_t expansions = 0;
  std::uint32_t until_poll = budget.check_interval;
  PlanStatus status = PlanStatus::kNoPath;
  std::uint32_t end = kNoParent;

  const auto relax = [&](std::uint32_t n, int col, int row, std::uint64_t g_new,
                         std::uint32_t from) {
    const std::uint32_t st = stamp[n];
    if (st == closed || (st == open && g_new >= gs[n]))
      return;
    gs[n] = g_new;
    parent[n] = from;
    stamp[n] = open;
    const std::uint64_t hn = heuristic(col, row);
    heap_.push_back({g_new + hn, saturate32(hn), n});
    std::push_heap(heap_.begin(), heap_.end(), later);
  };

  while (!heap_.empty()) {
    std::pop_heap(heap_.begin(), heap_.end(), later);
    const Entry e = heap_.back();
    heap_.pop_back();
    const std::uint32_t i = e.index;
    if (stamp[i] == closed)
      continue;  // stale duplicate (lazy deletion)
    stamp[i] = closed;
    ++expansions;
    const int col = static_cast<int>(i % uw), row = static_cast<int>(i / uw);
    if (options.record_expansions)
      result.expanded.push_back({col, row});
    if (i == goal) {
      status = PlanStatus::kFound;
      end = goal;
      break;
    }
    const std::uint64_t hi = e.f - gs[i];
    if (hi < best_h || (hi == best_h && gs[i] < gs[best])) {
      best_h = hi;
      best = i;
    }
    if (budget.max_expansions != 0 && expansions >= budget.max_expansions) {
      status = PlanStatus::kPartial;
      break;
    }
    if (polling && --until_poll == 0) {
      until_poll = budget.check_interval;
      if (budget.cancelled && budget.cancelled()) {
        status = PlanStatus::kCancelled;
        break;
      }
      if (timed && budget.now_s() - t0 >= budget.max_time_s) {
        status = PlanStatus::kPartial;
        break;
      }
    }
    const std::uint64_t gi = gs[i];
    if constexpr (kJump) {
      // Successors: scan from each direction that the parent direction does not prune.
      int pdc = 0, pdr = 0;
      if (parent[i] != kNoParent) {
        const int pc = static_cast<int>(parent[i] % uw), pr = static_cast<int>(parent[i] / uw);
        pdc = (col > pc) - (col < pc);
        pdr = (row > pr) - (row < pr);
      }
      const auto push_jump = [&](const std::optional<Cell>& jp) {
        if (!jp)
          return;
        const std::uint32_t n =
            static_cast<std::uint32_t>(jp->row) * uw + static_cast<std::uint32_t>(jp->col);
        relax(n, jp->col, jp->row, gi + octileCost({col, row}, *jp), i);
      };
      const auto straight = [&](int dc, int dr) {
        if (open_at(col + dc, row + dr))
          push_jump(jump_straight(col + dc, row + dr, dc, dr));
      };
      const auto diagonal = [&](int dc, int dr) {
        if (open_at(col + dc, row) && open_at(col, row + dr))
          push_jump(jump_diagonal(col + dc, row + dr, dc, dr));
      };
      if (pdc == 0 && pdr == 0) {
        for (const int dc : {-1, 1})
          straight(dc, 0);
        for (const int dr : {-1, 1})
          straight(0, dr);
        for (const int dc : {-1, 1})
          for (const int dr : {-1, 1})
            diagonal(dc, dr);
      } else if (pdc != 0 && pdr != 0) {
        straight(pdc, 0);
        straight(0, pdr);
        diagonal(pdc, pdr);
      } else if (pdc != 0) {
        straight(pdc, 0);
        for (const int dr : {-1, 1}) {
          straight(0, dr);
          diagonal(pdc, dr);
        }
      } else {
        straight(0, pdr);
        for (const int dc : {-1, 1}) {
          straight(dc, 0);
          diagonal(dc, pdr);
        }
      }
    } else {
      const bool has_l = col > 0, has_r = col + 1 < w, has_d = row > 0, has_u = row + 1 < h;
      const bool fl = has_l && free_at(i - 1);
      const bool fr = has_r && free_at(i + 1);
      const bool fd = has_d && free_at(i - uw);
      const bool fu = has_u && free_at(i + uw);
      const std::uint64_t gs_ = gi + kStraightCost, gd = gi + kDiagonalCost;
      if (fl)
        relax(i - 1, col - 1, row, gs_, i);
      if (fr)
        relax(i + 1, col + 1, row, gs_, i);
      if (fd)
        relax(i - uw, col, row - 1, gs_, i);
      if (fu)
        relax(i + uw, col, row + 1, gs_, i);
      if (fl && fd && free_at(i - uw - 1))
        relax(i - uw - 1, col - 1, row - 1, gd, i);
      if (fr && fd && free_at(i - uw + 1))
        relax(i - uw + 1, col + 1, row - 1, gd, i);
      if (fl && fu && free_at(i + uw - 1))
        relax(i + uw - 1, col - 1, row + 1, gd, i);
      if (fr && fu && free_at(i + uw + 1))
        relax(i + uw + 1, col + 1, row + 1, gd, i);
    }
  }
  if (status == PlanStatus::kPartial)
    end = best;
  result.status = status;
  result.expansions = expansions;
  if (end != kNoParent) {
    result.cost = gs[end];
    for (std::uint32_t c = end; c != kNoParent; c = parent[c]) {
      const Cell cell = grid.cellOf(c);
      if (!result.cells.empty()) {
        // Jump points are joined by straight or diagonal runs: fill in the cells between.
        const Cell prev = result.cells.back();
        const int dc = (cell.col > prev.col) - (cell.col < prev.col);
        const int dr = (cell.row > prev.row) - (cell.row < prev.row);
        for (Cell k{prev.col + dc, prev.row + dr}; !(k == cell); k = {k.col + dc, k.row + dr})
          result.cells.push_back(k);
      }
      result.cells.push_back(cell);
    }
    std::reverse(result.cells.begin(), result.cells.end());
    finishPlanResult(grid, result);
  }
  return result;
}

PlanResult planAStar(const PlanningGrid& grid, const Cell& start, const Cell& goal,
                     const AStarOptions& options) {
  AStarPlanner planner;
  return planner.plan(grid, start, goal, options);
}

PlanResult dijkstraReference(const PlanningGrid& grid, const Cell& start, const Cell& goal) {
  if (const auto status = precheck(grid, start, goal, nullptr, 0)) {
    PlanResult result;
    result.status = *status;
    return result;
  }
  return planToNearest(
      grid, start, [&goal](const Cell& c) { return c == goal; }, true);
}

}  // namespace irgs
