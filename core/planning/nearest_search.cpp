#include "core/planning/nearest_search.hpp"

#include <algorithm>
#include <limits>
#include <queue>
#include <utility>
#include <vector>

namespace irgs {

PlanResult planToNearest(const PlanningGrid& grid, const Cell& start, const GoalTest& is_goal,
                         bool start_may_be_goal) {
  PlanResult result;
  if (!grid.inside(start)) {
    result.status = PlanStatus::kOutOfBounds;
    return result;
  }
  if (!grid.isFree(start)) {
    result.status = PlanStatus::kStartBlocked;
    return result;
  }
  const std::size_t n = grid.cellCount();
  constexpr std::uint64_t kInf = std::numeric_limits<std::uint64_t>::max();
  std::vector<std::uint64_t> dist(n, kInf);
  std::vector<std::size_t> parent(n, n);
  std::vector<bool> done(n, false);
  using Item = std::pair<std::uint64_t, std::size_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
  const std::size_t s = grid.index(start);
  dist[s] = 0;
  queue.push({0, s});
  std::size_t found = n;
  while (!queue.empty()) {
    const auto [d, i] = queue.top();
    queue.pop();
    if (done[i])
      continue;
    done[i] = true;
    ++result.expansions;
    const Cell c = grid.cellOf(i);
    if ((i != s || start_may_be_goal) && is_goal(c)) {
      found = i;
      break;
    }
    for (int dr = -1; dr <= 1; ++dr)
      for (int dc = -1; dc <= 1; ++dc) {
        if (dc == 0 && dr == 0)
          continue;
        const Cell m{c.col + dc, c.row + dr};
        if (!grid.isFree(m))
          continue;
        if (dc != 0 && dr != 0 &&
            (!grid.isFree({c.col + dc, c.row}) || !grid.isFree({c.col, c.row + dr})))
          continue;
        const std::size_t j = grid.index(m);
        const std::uint64_t nd = d + (dc != 0 && dr != 0 ? kDiagonalCost : kStraightCost);
        if (nd < dist[j]) {
          dist[j] = nd;
          parent[j] = i;
          queue.push({nd, j});
        }
      }
  }
  if (found == n) {
    result.status = PlanStatus::kNoPath;
    return result;
  }
  result.status = PlanStatus::kFound;
  result.cost = dist[found];
  for (std::size_t i = found; i != n; i = parent[i])
    result.cells.push_back(grid.cellOf(i));
  std::reverse(result.cells.begin(), result.cells.end());
  finishPlanResult(grid, result);
  return result;
}

}  // namespace irgs
