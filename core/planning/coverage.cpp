#include "core/planning/coverage.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <stdexcept>

#include "core/planning/free_space.hpp"
#include "core/planning/path_amendment.hpp"

namespace irgs {
namespace {

// Lattice directions, counter-clockwise: +x, +y, -x, -y.
constexpr std::array<std::array<int, 2>, 4> kDir{{{1, 0}, {0, 1}, {-1, 0}, {0, -1}}};

struct Lattice {
  int cols = 0, rows = 0, lane = 1;
  std::vector<Cell> centre;        // fine cell at each node's centre
  std::vector<std::uint8_t> ok;    // node usable
  std::vector<std::uint8_t> link;  // bit d: edge to neighbour in direction d is free
  int index(int c, int r) const { return r * cols + c; }
};

Lattice buildLattice(const PlanningGrid& grid, int lane) {
  Lattice l;
  l.lane = lane;
  l.cols = (grid.width + lane - 1) / lane;
  l.rows = (grid.height + lane - 1) / lane;
  const auto n = static_cast<std::size_t>(l.cols) * static_cast<std::size_t>(l.rows);
  l.centre.resize(n);
  l.ok.assign(n, 0);
  l.link.assign(n, 0);
  for (int r = 0; r < l.rows; ++r)
    for (int c = 0; c < l.cols; ++c) {
      const Cell centre{std::min(grid.width - 1, c * lane + lane / 2),
                        std::min(grid.height - 1, r * lane + lane / 2)};
      const auto i = static_cast<std::size_t>(l.index(c, r));
      l.centre[i] = centre;
      l.ok[i] = grid.isFree(centre) ? 1 : 0;
    }
  for (int r = 0; r < l.rows; ++r)
    for (int c = 0; c < l.cols; ++c) {
      const auto i = static_cast<std::size_t>(l.index(c, r));
      if (!l.ok[i])
        continue;
      for (std::size_t d = 0; d < 4; ++d) {
        const int nc = c + kDir[d][0], nr = r + kDir[d][1];
        if (nc < 0 || nr < 0 || nc >= l.cols || nr >= l.rows)
          continue;
        const auto j = static_cast<std::size_t>(l.index(nc, nr));
        if (l.ok[j] &&
            segmentIsFree(grid, grid.cellCentre(l.centre[i]), grid.cellCentre(l.centre[j])))
          l.link[i] = static_cast<std::uint8_t>(l.link[i] | (1u << d));
      }
    }
  return l;
}

// Free cells reachable from start with the planner's moves (8-connected, no corner cutting).
std::vector<std::uint8_t> reachable(const PlanningGrid& grid, const Cell& start) {
  std::vector<std::uint8_t> seen(grid.cellCount(), 0);
  std::deque<Cell> queue{start};
  seen[grid.index(start)] = 1;
  while (!queue.empty()) {
    const Cell c = queue.front();
    queue.pop_front();
    for (int dr = -1; dr <= 1; ++dr)
      for (int dc = -1; dc <= 1; ++dc) {
        const Cell n{c.col + dc, c.row + dr};
        if ((dc == 0 && dr == 0) || !grid.isFree(n) || seen[grid.index(n)])
          continue;
        if (dc != 0 && dr != 0 &&
            (!grid.isFree({c.col + dc, c.row}) || !grid.isFree({c.col, c.row + dr})))
          continue;
        seen[grid.index(n)] = 1;
        queue.push_back(n);
      }
  }
  return seen;
}

}  // namespace

CoveragePlan planCoverage(const PlanningGrid& grid, const Cell& start,
                          const CoverageOptions& options) {
  if (options.lane_cells < 1)
    throw std::invalid_argument("planCoverage: lane_cells must be >= 1");
  CoveragePlan plan;
  if (!grid.isFree(start))
    return plan;
  const Lattice l = buildLattice(grid, options.lane_cells);
  // Enter the lattice at the usable node nearest the start that the start can see.
  int cur = -1;
  double best = 1e300;
  for (int i = 0; i < static_cast<int>(l.ok.size()); ++i) {
    const auto ui = static_cast<std::size_t>(i);
    if (!l.ok[ui])
      continue;
    const double d = (grid.cellCentre(l.centre[ui]) - grid.cellCentre(start)).norm();
    if (d < best && segmentIsFree(grid, grid.cellCentre(start), grid.cellCentre(l.centre[ui]))) {
      best = d;
      cur = i;
    }
  }
  plan.ok = true;
  plan.points.push_back(grid.cellCentre(start));
  std::vector<std::uint8_t> visited(l.ok.size(), 0);
  if (cur >= 0) {
    plan.points.push_back(grid.cellCentre(l.centre[static_cast<std::size_t>(cur)]));
    visited[static_cast<std::size_t>(cur)] = 1;
    std::size_t dir = 0;       // current heading on the lattice
    std::size_t vertical = 1;  // boustrophedon: the direction of the lane steps (+y first)
    const auto step = [&](int i, std::size_t d) {
      const int c = i % l.cols + kDir[d][0], r = i / l.cols + kDir[d][1];
      return l.index(c, r);
    };
    const auto can = [&](int i, std::size_t d) {
      return ((l.link[static_cast<std::size_t>(i)] >> d) & 1u) != 0 &&
             !visited[static_cast<std::size_t>(step(i, d))];
    };
    for (;;) {
      std::array<std::size_t, 4> order{};
      if (options.pattern == CoveragePattern::kSpiral) {
        order = {dir, (dir + 3) % 4, (dir + 1) % 4, (dir + 2) % 4};  // straight, right, left, back
      } else {
        const std::size_t along = (dir == 0 || dir == 2) ? dir : 0;
        order = {along, vertical, (along + 2) % 4, (vertical + 2) % 4};
      }
      bool moved = false;
      for (const std::size_t d : order)
        if (can(cur, d)) {
          if (options.pattern == CoveragePattern::kBoustrophedon && (d == 1 || d == 3)) {
            vertical = d;
            dir = (dir == 0 || dir == 2) ? (dir + 2) % 4 : 2;  // next lane runs back
          } else {
            dir = d;
          }
          cur = step(cur, d);
          visited[static_cast<std::size_t>(cur)] = 1;
          plan.points.push_back(grid.cellCentre(l.centre[static_cast<std::size_t>(cur)]));
          moved = true;
          break;
        }
      if (moved)
        continue;
      // Boxed in: breadth-first over the lattice to the nearest unvisited node.
      std::vector<int> parent(l.ok.size(), -1);
      std::deque<int> queue{cur};
      parent[static_cast<std::size_t>(cur)] = cur;
      int target = -1;
      while (!queue.empty() && target < 0) {
        const int i = queue.front();
        queue.pop_front();
        for (std::size_t d = 0; d < 4; ++d) {
          if (((l.link[static_cast<std::size_t>(i)] >> d) & 1u) == 0)
            continue;
          const int j = step(i, d);
          if (parent[static_cast<std::size_t>(j)] >= 0)
            continue;
          parent[static_cast<std::size_t>(j)] = i;
          if (!visited[static_cast<std::size_t>(j)]) {
            target = j;
            break;
          }
          queue.push_back(j);
        }
      }
      if (target < 0)
        break;
      std::vector<int> route;
      for (int i = target; i != cur; i = parent[static_cast<std::size_t>(i)])
        route.push_back(i);
      std::reverse(route.begin(), route.end());
      for (const int i : route)
        plan.points.push_back(grid.cellCentre(l.centre[static_cast<std::size_t>(i)]));
      const int before = route.size() > 1 ? route[route.size() - 2] : cur;
      for (std::size_t d = 0; d < 4; ++d)
        if (step(before, d) == target && ((l.link[static_cast<std::size_t>(before)] >> d) & 1u))
          dir = d;
      cur = target;
      visited[static_cast<std::size_t>(cur)] = 1;
      ++plan.jumps;
    }
  }
  plan.points = compressPath(plan.points);
  plan.length_m = pathLength(plan.points);
  plan.turns = countTurns(plan.points);
  // Coverage: reachable free cells within half a lane of a path segment.
  const std::vector<std::uint8_t> reach = reachable(grid, start);
  std::vector<std::uint8_t> covered(grid.cellCount(), 0);
  const double half = 0.5 * options.lane_cells * grid.resolution_m + 1e-9;
  const auto mark_segment = [&](const Vec2& a, const Vec2& b) {
    Box2 box;
    box.extend(a);
    box.extend(b);
    const int c0 = std::max(0, static_cast<int>(std::floor((box.min.x() - half - grid.origin.x()) /
                                                           grid.resolution_m)));
    const int r0 = std::max(0, static_cast<int>(std::floor((box.min.y() - half - grid.origin.y()) /
                                                           grid.resolution_m)));
    const int c1 =
        std::min(grid.width - 1,
                 static_cast<int>((box.max.x() + half - grid.origin.x()) / grid.resolution_m));
    const int r1 =
        std::min(grid.height - 1,
                 static_cast<int>((box.max.y() + half - grid.origin.y()) / grid.resolution_m));
    const Vec2 ab = b - a;
    const double len2 = ab.squaredNorm();
    for (int r = r0; r <= r1; ++r)
      for (int c = c0; c <= c1; ++c) {
        const Vec2 p = grid.cellCentre({c, r});
        const double t = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
        if ((a + t * ab - p).norm() <= half)
          covered[grid.index({c, r})] = 1;
      }
  };
  for (std::size_t i = 1; i < plan.points.size(); ++i)
    mark_segment(plan.points[i - 1], plan.points[i]);
  if (plan.points.size() == 1)
    mark_segment(plan.points[0], plan.points[0]);
  for (std::size_t i = 0; i < reach.size(); ++i) {
    plan.reachable_cells += reach[i];
    plan.covered_cells += reach[i] && covered[i] ? 1 : 0;
  }
  plan.coverage = plan.reachable_cells == 0 ? 0.0
                                            : static_cast<double>(plan.covered_cells) /
                                                  static_cast<double>(plan.reachable_cells);
  return plan;
}

}  // namespace irgs
