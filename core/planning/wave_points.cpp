#include "core/planning/wave_points.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>
#include <stdexcept>

#include "core/planning/distance_transform.hpp"

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

// Exact costs between the end points of each region's entrances.
void linkRegions(const PlanningGrid& grid, WaveRegions& out) {
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

  linkRegions(grid, out);
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

std::optional<std::string> doorwayOptionsError(const DoorwayOptions& o) {
  if (!std::isfinite(o.min_width_m) || !std::isfinite(o.max_width_m) || o.min_width_m <= 0.0 ||
      o.min_width_m > o.max_width_m)
    return "doorway widths must be finite with 0 < min_width_m <= max_width_m";
  if (!std::isfinite(o.depth_m) || o.depth_m <= 0.0)
    return "doorway depth_m must be finite and > 0";
  if (!std::isfinite(o.open_ratio) || o.open_ratio <= 1.0)
    return "doorway open_ratio must be finite and > 1";
  if (o.directions < 4 || o.directions > 720)
    return "doorway directions must be in [4, 720]";
  return std::nullopt;
}

namespace {

struct DoorCandidate {
  std::size_t index = 0;
  Doorway door;
};

// Distance (m) from p along unit u to the first blocked or outside sample, sampled every half
// cell, up to limit_m (returns limit_m + 1 when nothing is hit before it).
double freeRun(const PlanningGrid& grid, const Vec2& p, const Vec2& u, double limit_m) {
  const double step = 0.5 * grid.resolution_m;
  for (double t = step; t <= limit_m + step; t += step) {
    const auto c = grid.worldToCell(p + t * u);
    if (!c || !grid.isFree(*c))
      return t - 0.5 * step;  // the boundary lies between the last free and this sample
  }
  return limit_m + 1.0;
}

}  // namespace

std::vector<Doorway> detectDoorways(const PlanningGrid& grid, const DoorwayOptions& options) {
  if (const auto error = doorwayOptionsError(options))
    throw std::invalid_argument(*error);
  std::vector<Doorway> out;
  if (grid.empty() || grid.blockedCount() == 0)
    return out;
  const double res = grid.resolution_m;
  const std::vector<double> d2 = squaredDistanceTransform(grid.blocked, grid.width, grid.height);
  const auto d2At = [&](int col, int row) {
    return grid.inside({col, row}) ? d2[grid.index({col, row})] : 0.0;
  };
  std::vector<Vec2> dirs;
  for (int k = 0; k < options.directions; ++k) {
    const double a = kPi * k / options.directions;
    dirs.emplace_back(std::cos(a), std::sin(a));
  }
  std::vector<DoorCandidate> candidates;
  std::vector<std::int32_t> candidate_of(grid.cellCount(), -1);
  for (int row = 0; row < grid.height; ++row)
    for (int col = 0; col < grid.width; ++col) {
      const Cell c{col, row};
      if (!grid.isFree(c))
        continue;
      const double here = d2[grid.index(c)];
      // Half the passage width is about the clearance (centre to blocked centre) less half a
      // cell; allow a cell of slack either way before the exact chord test.
      const double half_width = std::sqrt(here) * res - 0.5 * res;
      if (2.0 * half_width < options.min_width_m - 2.0 * res ||
          2.0 * half_width > options.max_width_m + 2.0 * res)
        continue;
      bool ridge = false;
      for (const auto& [dc, dr] :
           {std::pair{1, 0}, std::pair{0, 1}, std::pair{1, 1}, std::pair{1, -1}})
        ridge = ridge || (d2At(col + dc, row + dr) <= here && d2At(col - dc, row - dr) <= here);
      if (!ridge)
        continue;
      // The shortest free chord through the cell centre.
      const Vec2 p = grid.cellCentre(c);
      double best = std::numeric_limits<double>::infinity(), best_fwd = 0.0, best_back = 0.0;
      std::size_t best_k = 0;
      for (std::size_t k = 0; k < dirs.size(); ++k) {
        const double fwd = freeRun(grid, p, dirs[k], options.max_width_m);
        if (fwd > options.max_width_m)
          continue;
        const double back = freeRun(grid, p, -dirs[k], options.max_width_m - fwd + res);
        if (fwd + back < best) {
          best = fwd + back;
          best_fwd = fwd;
          best_back = back;
          best_k = k;
        }
      }
      if (best < options.min_width_m || best > options.max_width_m)
        continue;
      // Both sides must open up within depth_m.
      const Vec2 normal(-dirs[best_k].y(), dirs[best_k].x());
      const double open_d2 = std::pow(options.open_ratio * 0.5 * best / res, 2);
      bool opens = true;
      for (const double side : {1.0, -1.0}) {
        bool side_opens = false;
        for (double t = 0.5 * res; t <= options.depth_m && !side_opens; t += 0.5 * res) {
          const auto q = grid.worldToCell(p + side * t * normal);
          if (!q || !grid.isFree(*q))
            break;
          side_opens = d2[grid.index(*q)] >= open_d2;
        }
        opens = opens && side_opens;
      }
      if (!opens)
        continue;
      DoorCandidate cand;
      cand.index = grid.index(c);
      cand.door.cell = c;
      cand.door.centre = p;
      cand.door.width_m = best;
      cand.door.direction_rad = kPi * static_cast<double>(best_k) / options.directions;
      cand.door.jamb_a = p - best_back * dirs[best_k];
      cand.door.jamb_b = p + best_fwd * dirs[best_k];
      candidate_of[cand.index] = static_cast<std::int32_t>(candidates.size());
      candidates.push_back(cand);
    }
  // One doorway per 8-connected group of candidates: the narrowest (first in row-major order
  // among equals).
  std::vector<std::uint8_t> seen(candidates.size(), 0);
  std::vector<std::size_t> stack;
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if (seen[i] != 0)
      continue;
    seen[i] = 1;
    stack.push_back(i);
    std::size_t best = i;
    while (!stack.empty()) {
      const std::size_t k = stack.back();
      stack.pop_back();
      if (candidates[k].door.width_m < candidates[best].door.width_m ||
          (candidates[k].door.width_m == candidates[best].door.width_m &&
           candidates[k].index < candidates[best].index))
        best = k;
      const Cell c = candidates[k].door.cell;
      for (int dr = -1; dr <= 1; ++dr)
        for (int dc = -1; dc <= 1; ++dc) {
          const Cell n{c.col + dc, c.row + dr};
          if (!grid.inside(n))
            continue;
          const std::int32_t j = candidate_of[grid.index(n)];
          if (j >= 0 && seen[static_cast<std::size_t>(j)] == 0) {
            seen[static_cast<std::size_t>(j)] = 1;
            stack.push_back(static_cast<std::size_t>(j));
          }
        }
    }
    out.push_back(candidates[best].door);
  }
  // One passage can leave two groups (e.g. a chord from one jamb to the far side of the other
  // beside the true door line): keep the narrowest of doorways whose centres lie on another's
  // door line.
  std::stable_sort(out.begin(), out.end(),
                   [](const Doorway& a, const Doorway& b) { return a.width_m < b.width_m; });
  std::vector<Doorway> kept;
  for (const Doorway& d : out) {
    bool duplicate = false;
    for (const Doorway& k : kept) {
      const Vec2 ab = k.jamb_b - k.jamb_a;
      const double t = std::clamp((d.centre - k.jamb_a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
      duplicate = duplicate || (k.jamb_a + t * ab - d.centre).norm() < 0.5 * k.width_m;
    }
    if (!duplicate)
      kept.push_back(d);
  }
  out = std::move(kept);
  std::sort(out.begin(), out.end(), [](const Doorway& a, const Doorway& b) {
    return a.cell.row != b.cell.row ? a.cell.row < b.cell.row : a.cell.col < b.cell.col;
  });
  return out;
}

WaveRegions partitionAtDoorways(const PlanningGrid& grid, const std::vector<Doorway>& doorways) {
  WaveRegions out;
  out.block_cells = 0;
  out.region_of_cell.assign(grid.cellCount(), -1);
  // Door lines as 4-connected cell chains, extended by one cell past each jamb.
  std::vector<std::uint8_t> cut(grid.cellCount(), 0);
  for (const Doorway& d : doorways) {
    if (!grid.inside(d.cell))
      throw std::invalid_argument("partitionAtDoorways: a doorway lies outside the grid");
    const Vec2 u(std::cos(d.direction_rad), std::sin(d.direction_rad));
    const Vec2 a = d.jamb_a - grid.resolution_m * u, b = d.jamb_b + grid.resolution_m * u;
    const double step = 0.125 * grid.resolution_m;
    const int n = static_cast<int>(std::ceil((b - a).norm() / step));
    std::optional<Cell> last;
    for (int k = 0; k <= n; ++k) {
      const auto c = grid.worldToCell(a + (static_cast<double>(k) / std::max(n, 1)) * (b - a));
      if (!c)
        continue;
      if (last && last->col != c->col && last->row != c->row) {
        const Cell bridge{c->col, last->row};  // keep the chain 4-connected
        cut[grid.index(bridge)] = 1;
      }
      cut[grid.index(*c)] = 1;
      last = c;
    }
  }
  // 4-connected regions of the free, uncut cells.
  const auto fill = [&](const Cell& seed, std::int32_t id, bool through_cut) {
    std::vector<Cell> stack{seed};
    out.region_of_cell[grid.index(seed)] = id;
    while (!stack.empty()) {
      const Cell k = stack.back();
      stack.pop_back();
      for (const Cell nb : {Cell{k.col + 1, k.row}, Cell{k.col - 1, k.row}, Cell{k.col, k.row + 1},
                            Cell{k.col, k.row - 1}}) {
        if (!grid.isFree(nb) || out.region_of_cell[grid.index(nb)] >= 0 ||
            (cut[grid.index(nb)] != 0) != through_cut)
          continue;
        out.region_of_cell[grid.index(nb)] = id;
        stack.push_back(nb);
      }
    }
  };
  for (int r = 0; r < grid.height; ++r)
    for (int c = 0; c < grid.width; ++c)
      if (grid.isFree({c, r}) && cut[grid.index({c, r})] == 0 &&
          out.region_of_cell[grid.index({c, r})] < 0)
        fill({c, r}, out.region_count++, false);
  // Cut cells join a neighbouring region, preferring the one on the door's +normal side;
  // repeated so cut cells reached only through other cut cells join too.
  for (bool changed = true; changed;) {
    changed = false;
    for (int r = 0; r < grid.height; ++r)
      for (int c = 0; c < grid.width; ++c) {
        const Cell k{c, r};
        if (!grid.isFree(k) || cut[grid.index(k)] == 0 || out.region_of_cell[grid.index(k)] >= 0)
          continue;
        std::int32_t pick = -1;
        double best_side = -std::numeric_limits<double>::infinity();
        for (const Cell nb : {Cell{c + 1, r}, Cell{c - 1, r}, Cell{c, r + 1}, Cell{c, r - 1}}) {
          if (!grid.isFree(nb) || out.region_of_cell[grid.index(nb)] < 0)
            continue;
          // +normal of the nearest doorway (approximated by the first doorway whose line
          // passes here: the side only orders the choice, any neighbour is correct).
          double side = 0.0;
          for (const Doorway& d : doorways) {
            const Vec2 nrm(-std::sin(d.direction_rad), std::cos(d.direction_rad));
            const Vec2 off = grid.cellCentre(k) - d.centre;
            if (std::abs(off.dot(nrm)) <= grid.resolution_m &&
                std::abs(off.dot(Vec2(nrm.y(), -nrm.x()))) <= 0.5 * d.width_m + grid.resolution_m) {
              side = (grid.cellCentre(nb) - grid.cellCentre(k)).dot(nrm);
              break;
            }
          }
          if (side > best_side) {
            best_side = side;
            pick = out.region_of_cell[grid.index(nb)];
          }
        }
        if (pick >= 0) {
          out.region_of_cell[grid.index(k)] = pick;
          changed = true;
        }
      }
  }
  for (int r = 0; r < grid.height; ++r)  // cut cells cut off from everything: own regions
    for (int c = 0; c < grid.width; ++c)
      if (grid.isFree({c, r}) && out.region_of_cell[grid.index({c, r})] < 0)
        fill({c, r}, out.region_count++, true);
  // One entrance per separating doorway: its wave point and the 4-neighbour across the line.
  for (const Doorway& d : doorways) {
    if (!grid.isFree(d.cell))
      continue;  // closed by inflation: the robot does not fit through
    const std::int32_t ra = out.region_of_cell[grid.index(d.cell)];
    const Vec2 nrm(-std::sin(d.direction_rad), std::cos(d.direction_rad));
    const Cell c = d.cell;
    std::optional<Cell> across;
    double best_side = std::numeric_limits<double>::infinity();
    for (const Cell nb : {Cell{c.col + 1, c.row}, Cell{c.col - 1, c.row}, Cell{c.col, c.row + 1},
                          Cell{c.col, c.row - 1}}) {
      if (!grid.isFree(nb) || out.region_of_cell[grid.index(nb)] == ra)
        continue;
      const double side = (grid.cellCentre(nb) - grid.cellCentre(c)).dot(nrm);
      if (side < best_side) {
        best_side = side;
        across = nb;
      }
    }
    if (!across)
      continue;  // both sides are one region: the gap separates nothing
    out.entrances.push_back({ra, out.region_of_cell[grid.index(*across)], c, *across});
  }
  linkRegions(grid, out);
  return out;
}

}  // namespace irgs
