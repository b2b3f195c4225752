#include "core/planning/wave_points.hpp"

#include <algorithm>
#include <limits>
#include <queue>
#include <stdexcept>

namespace irgs {
namespace {

// Appends leg (which starts at the last cell of plan) to plan.
void append(WavePlan& plan, const PlanResult& leg) {
  const std::size_t skip = plan.cells.empty() ? 0 : 1;
  plan.cells.insert(plan.cells.end(), leg.cells.begin() + static_cast<std::ptrdiff_t>(skip),
                    leg.cells.end());
  plan.cost += leg.cost;
}

void finish(const PlanningGrid& grid, WavePlan& plan) {
  plan.points.clear();
  for (const Cell& c : plan.cells)
    plan.points.push_back(grid.cellCentre(c));
  plan.cost_m =
      static_cast<double>(plan.cost) / static_cast<double>(kStraightCost) * grid.resolution_m;
}

}  // namespace

WaveRegions partitionIntoBlocks(const PlanningGrid& grid, int block_cells) {
  if (block_cells < 2)
    throw std::invalid_argument("partitionIntoBlocks: block_cells must be >= 2");
  WaveRegions out;
  out.block_cells = block_cells;
  out.region_of_cell.assign(grid.cellCount(), -1);
  const auto block_of = [block_cells](const Cell& c) {
    return std::pair{c.col / block_cells, c.row / block_cells};
  };
  // Flood fill (4-connected) inside each block.
  std::vector<Cell> stack;
  for (int r = 0; r < grid.height; ++r)
    for (int c = 0; c < grid.width; ++c) {
      if (!grid.isFree({c, r}) || out.region_of_cell[grid.index({c, r})] >= 0)
        continue;
      const std::int32_t id = out.region_count++;
      const auto blk = block_of({c, r});
      stack.push_back({c, r});
      out.region_of_cell[grid.index({c, r})] = id;
      while (!stack.empty()) {
        const Cell k = stack.back();
        stack.pop_back();
        for (const Cell n : {Cell{k.col + 1, k.row}, Cell{k.col - 1, k.row}, Cell{k.col, k.row + 1},
                             Cell{k.col, k.row - 1}}) {
          if (!grid.isFree(n) || block_of(n) != blk || out.region_of_cell[grid.index(n)] >= 0)
            continue;
          out.region_of_cell[grid.index(n)] = id;
          stack.push_back(n);
        }
      }
    }
  // Entrances: runs of touching pairs along each block border (vertical borders, then
  // horizontal), one wave point in the middle of each run.
  const auto region = [&](const Cell& c) {
    return grid.inside(c) ? out.region_of_cell[grid.index(c)] : -1;
  };
  const auto scan_border = [&](Cell first, Cell step, Cell across, int length) {
    int run_start = -1;
    std::int32_t ra = -1, rb = -1;
    for (int k = 0; k <= length; ++k) {
      const Cell a{first.col + step.col * k, first.row + step.row * k};
      const Cell b{a.col + across.col, a.row + across.row};
      const std::int32_t xa = k < length ? region(a) : -1, xb = k < length ? region(b) : -1;
      const bool same_run = run_start >= 0 && xa == ra && xb == rb;
      if (run_start >= 0 && !same_run) {
        const int mid = (run_start + k - 1) / 2;
        const Cell wa{first.col + step.col * mid, first.row + step.row * mid};
        out.entrances.push_back({ra, rb, wa, {wa.col + across.col, wa.row + across.row}});
        run_start = -1;
      }
      if (run_start < 0 && xa >= 0 && xb >= 0) {
        run_start = k;
        ra = xa;
        rb = xb;
      }
    }
  };
  for (int c = block_cells - 1; c + 1 < grid.width; c += block_cells)
    scan_border({c, 0}, {0, 1}, {1, 0}, grid.height);
  for (int r = block_cells - 1; r + 1 < grid.height; r += block_cells)
    scan_border({0, r}, {1, 0}, {0, 1}, grid.width);

  // Exact costs between the end points of each region's entrances.
  std::vector<std::vector<std::uint32_t>> nodes_of(static_cast<std::size_t>(out.region_count));
  for (std::size_t e = 0; e < out.entrances.size(); ++e) {
    nodes_of[static_cast<std::size_t>(out.entrances[e].region_a)].push_back(
        static_cast<std::uint32_t>(2 * e));
    nodes_of[static_cast<std::size_t>(out.entrances[e].region_b)].push_back(
        static_cast<std::uint32_t>(2 * e + 1));
  }
  const auto node_cell = [&out](std::uint32_t n) {
    const Entrance& e = out.entrances[n / 2];
    return n % 2 == 0 ? e.a : e.b;
  };
  AStarPlanner planner;
  AStarOptions opt;
  opt.region_of_cell = &out.region_of_cell;
  for (std::size_t reg = 0; reg < nodes_of.size(); ++reg) {
    opt.region = static_cast<std::int32_t>(reg);
    const auto& nodes = nodes_of[reg];
    for (std::size_t i = 0; i < nodes.size(); ++i)
      for (std::size_t j = i + 1; j < nodes.size(); ++j) {
        const PlanResult r = planner.plan(grid, node_cell(nodes[i]), node_cell(nodes[j]), opt);
        out.build_expansions += r.expansions;
        if (r.found())
          out.links.push_back({nodes[i], nodes[j], r.cost});
      }
  }
  return out;
}

WavePlan planWithWavePoints(const PlanningGrid& grid, const WaveRegions& regions, const Cell& start,
                            const Cell& goal, const AStarOptions& options) {
  if (regions.region_of_cell.size() != grid.cellCount())
    throw std::invalid_argument("planWithWavePoints: regions do not match the grid");
  if (options.region_of_cell != nullptr)
    throw std::invalid_argument("planWithWavePoints: options.region_of_cell must be null");
  WavePlan plan;
  if (!grid.inside(start) || !grid.inside(goal)) {
    plan.status = PlanStatus::kOutOfBounds;
    return plan;
  }
  if (!grid.isFree(start) || !grid.isFree(goal)) {
    plan.status = grid.isFree(start) ? PlanStatus::kGoalBlocked : PlanStatus::kStartBlocked;
    return plan;
  }
  AStarPlanner planner;
  AStarOptions opt = options;
  opt.region_of_cell = &regions.region_of_cell;
  const std::int32_t rs = regions.region_of_cell[grid.index(start)];
  const std::int32_t rg = regions.region_of_cell[grid.index(goal)];
  if (rs == rg) {
    opt.region = rs;
    const PlanResult r = planner.plan(grid, start, goal, opt);
    plan.expansions = r.expansions;
    plan.status = r.status;
    append(plan, r);
    finish(grid, plan);
    return plan;
  }
  // Region graph: entrance end points, plus start (node S) and goal (node S + 1).
  const auto entrance_nodes = static_cast<std::uint32_t>(2 * regions.entrances.size());
  const std::uint32_t s_node = entrance_nodes, g_node = entrance_nodes + 1;
  std::vector<std::vector<std::pair<std::uint32_t, std::uint64_t>>> adj(entrance_nodes + 2);
  for (std::size_t e = 0; e < regions.entrances.size(); ++e) {
    const auto a = static_cast<std::uint32_t>(2 * e);
    adj[a].push_back({a + 1, kStraightCost});
    adj[a + 1].push_back({a, kStraightCost});
  }
  for (const auto& l : regions.links) {
    adj[l.u].push_back({l.v, l.cost});
    adj[l.v].push_back({l.u, l.cost});
  }
  const auto node_cell = [&](std::uint32_t n) {
    if (n == s_node)
      return start;
    if (n == g_node)
      return goal;
    const Entrance& e = regions.entrances[n / 2];
    return n % 2 == 0 ? e.a : e.b;
  };
  const auto node_region = [&](std::uint32_t n) {
    return regions.region_of_cell[grid.index(node_cell(n))];
  };
  // Start and goal join their regions' end points with exact in-region costs.
  for (std::uint32_t n = 0; n < entrance_nodes; ++n) {
    const std::int32_t reg = node_region(n);
    for (const std::uint32_t end : {s_node, g_node}) {
      if (reg != node_region(end))
        continue;
      opt.region = reg;
      const PlanResult r = planner.plan(grid, node_cell(end), node_cell(n), opt);
      plan.expansions += r.expansions;
      if (r.status == PlanStatus::kCancelled) {
        plan.status = r.status;
        return plan;
      }
      if (r.found()) {
        adj[end].push_back({n, r.cost});
        adj[n].push_back({end, r.cost});
      }
    }
  }
  // Dijkstra over the region graph.
  constexpr std::uint64_t kInf = std::numeric_limits<std::uint64_t>::max();
  std::vector<std::uint64_t> dist(adj.size(), kInf);
  std::vector<std::uint32_t> prev(adj.size(), std::numeric_limits<std::uint32_t>::max());
  using Item = std::pair<std::uint64_t, std::uint32_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
  dist[s_node] = 0;
  queue.push({0, s_node});
  while (!queue.empty()) {
    const auto [d, u] = queue.top();
    queue.pop();
    if (d != dist[u])
      continue;
    if (u == g_node)
      break;
    for (const auto& [v, w] : adj[u])
      if (d + w < dist[v]) {
        dist[v] = d + w;
        prev[v] = u;
        queue.push({dist[v], v});
      }
  }
  if (dist[g_node] == kInf) {
    plan.status = PlanStatus::kNoPath;
    return plan;
  }
  std::vector<std::uint32_t> route;
  for (std::uint32_t n = g_node; n != s_node; n = prev[n])
    route.push_back(n);
  route.push_back(s_node);
  std::reverse(route.begin(), route.end());
  // Region by region: consecutive nodes in one region are joined by a confined A*; an
  // entrance's two end points by the single step between them (a wave point crossing).
  plan.cells.push_back(start);
  for (std::size_t k = 1; k < route.size(); ++k) {
    const Cell from = node_cell(route[k - 1]), to = node_cell(route[k]);
    if (node_region(route[k - 1]) != node_region(route[k])) {
      plan.wave_indices.push_back(plan.cells.size() - 1);
      plan.cells.push_back(to);
      plan.cost += kStraightCost;
      continue;
    }
    opt.region = node_region(route[k]);
    const PlanResult r = planner.plan(grid, from, to, opt);
    plan.expansions += r.expansions;
    if (r.status == PlanStatus::kPartial || r.found())
      append(plan, r);
    if (!r.found()) {
      plan.status = r.status;
      finish(grid, plan);
      return plan;
    }
  }
  plan.status = PlanStatus::kFound;
  finish(grid, plan);
  return plan;
}

WavePlan planThroughWavePoints(const PlanningGrid& grid, const Cell& start, const Cell& goal,
                               const std::vector<Cell>& wave_points, const AStarOptions& options) {
  WavePlan plan;
  AStarPlanner planner;
  std::vector<Cell> stops{start};
  stops.insert(stops.end(), wave_points.begin(), wave_points.end());
  stops.push_back(goal);
  for (std::size_t k = 1; k < stops.size(); ++k) {
    const PlanResult r = planner.plan(grid, stops[k - 1], stops[k], options);
    plan.expansions += r.expansions;
    if (r.found() || r.status == PlanStatus::kPartial)
      append(plan, r);
    if (!r.found()) {
      plan.status = r.status;
      finish(grid, plan);
      return plan;
    }
    if (k + 1 < stops.size())
      plan.wave_indices.push_back(plan.cells.size() - 1);
  }
  plan.status = PlanStatus::kFound;
  finish(grid, plan);
  return plan;
}

}  // namespace irgs
