// A* of core/planning (AStarPlanner, jump points and plain) beside boost::astar_search on the
// same grids, same run.
// Grids: N x N cells, N in {500, 2000, 5000}, random axis-aligned rectangles (sides 1..N/50
// cells, seeded) until 20 % of the cells are blocked, 8 x 8 cells cleared at two opposite
// corners; the query runs corner to corner. A map whose corners are not connected is
// regenerated with the next seed, so every query has a path.
//
// Boost runs on an implicit 8-connected graph over the same PlanningGrid (no corner cutting,
// the same integer step costs), with dense vector property maps allocated once outside the
// timed loop ("maps reused"): its only per-query work is the algorithm itself, including the
// O(V) initialisation astar_search performs. Costs are asserted equal before timing.

#include <benchmark/benchmark.h>

#include <array>
#include <boost/graph/astar_search.hpp>
#include <boost/graph/graph_traits.hpp>
#include <boost/iterator/counting_iterator.hpp>
#include <boost/iterator/iterator_facade.hpp>
#include <boost/property_map/function_property_map.hpp>
#include <boost/property_map/property_map.hpp>
#include <cstdint>
#include <limits>
#include <map>
#include <memory>
#include <random>
#include <vector>

#include "core/planning/astar.hpp"

namespace irgs::bench {

// ---- The implicit graph boost searches -------------------------------------------------------

struct ImplicitGrid {
  const PlanningGrid* grid;
};

struct GridEdge {
  std::uint32_t u = 0;
  std::uint32_t v = 0;
  bool diagonal = false;
  friend bool operator==(const GridEdge&, const GridEdge&) = default;
};

constexpr std::array<std::array<int, 2>, 8> kDirs{
    {{1, 0}, {-1, 0}, {0, 1}, {0, -1}, {1, 1}, {-1, 1}, {1, -1}, {-1, -1}}};

// The same move rule as AStarPlanner: in the grid, free, no corner cutting.
inline bool moveValid(const PlanningGrid& g, const Cell& c, int dir) {
  const int dc = kDirs[static_cast<std::size_t>(dir)][0];
  const int dr = kDirs[static_cast<std::size_t>(dir)][1];
  if (!g.isFree({c.col + dc, c.row + dr}))
    return false;
  return dc == 0 || dr == 0 || (g.isFree({c.col + dc, c.row}) && g.isFree({c.col, c.row + dr}));
}

class OutEdgeIterator : public boost::iterator_facade<OutEdgeIterator, GridEdge,
                                                      boost::forward_traversal_tag, GridEdge> {
 public:
  OutEdgeIterator() = default;
  OutEdgeIterator(const PlanningGrid* g, std::uint32_t u, int dir)
      : g_(g), u_(u), cell_(g->cellOf(u)), dir_(dir) {
    skip();
  }

 private:
  friend class boost::iterator_core_access;
  void skip() {
    while (dir_ < 8 && !moveValid(*g_, cell_, dir_))
      ++dir_;
  }
  GridEdge dereference() const {
    const int dc = kDirs[static_cast<std::size_t>(dir_)][0];
    const int dr = kDirs[static_cast<std::size_t>(dir_)][1];
    return {u_, static_cast<std::uint32_t>(g_->index({cell_.col + dc, cell_.row + dr})),
            dc != 0 && dr != 0};
  }
  bool equal(const OutEdgeIterator& o) const { return u_ == o.u_ && dir_ == o.dir_; }
  void increment() {
    ++dir_;
    skip();
  }
  const PlanningGrid* g_ = nullptr;
  std::uint32_t u_ = 0;
  Cell cell_;
  int dir_ = 8;
};

inline std::uint32_t source(const GridEdge& e, const ImplicitGrid&) {
  return e.u;
}
inline std::uint32_t target(const GridEdge& e, const ImplicitGrid&) {
  return e.v;
}
inline std::pair<OutEdgeIterator, OutEdgeIterator> out_edges(std::uint32_t u,
                                                             const ImplicitGrid& g) {
  return {OutEdgeIterator(g.grid, u, 0), OutEdgeIterator(g.grid, u, 8)};
}
inline std::uint32_t out_degree(std::uint32_t u, const ImplicitGrid& g) {
  std::uint32_t n = 0;
  for (auto [it, end] = out_edges(u, g); it != end; ++it)
    ++n;
  return n;
}
inline std::pair<boost::counting_iterator<std::uint32_t>, boost::counting_iterator<std::uint32_t>>
vertices(const ImplicitGrid& g) {
  return {boost::counting_iterator<std::uint32_t>(0),
          boost::counting_iterator<std::uint32_t>(static_cast<std::uint32_t>(g.grid->cellCount()))};
}
inline std::uint32_t num_vertices(const ImplicitGrid& g) {
  return static_cast<std::uint32_t>(g.grid->cellCount());
}

}  // namespace irgs::bench

namespace boost {
template <>
struct graph_traits<irgs::bench::ImplicitGrid> {
  using vertex_descriptor = std::uint32_t;
  using edge_descriptor = irgs::bench::GridEdge;
  using directed_category = directed_tag;
  using edge_parallel_category = disallow_parallel_edge_tag;
  struct traversal_category : incidence_graph_tag, vertex_list_graph_tag {};
  using out_edge_iterator = irgs::bench::OutEdgeIterator;
  using vertex_iterator = counting_iterator<std::uint32_t>;
  using degree_size_type = std::uint32_t;
  using vertices_size_type = std::uint32_t;
  using edges_size_type = std::size_t;
  using in_edge_iterator = void;
  using edge_iterator = void;
  using adjacency_iterator = void;
  static vertex_descriptor null_vertex() { return std::numeric_limits<std::uint32_t>::max(); }
};
}  // namespace boost

namespace irgs::bench {
namespace {

struct FoundGoal {};

struct GoalVisitor : boost::default_astar_visitor {
  std::uint32_t goal;
  explicit GoalVisitor(std::uint32_t g) : goal(g) {}
  void examine_vertex(std::uint32_t u, const ImplicitGrid&) const {
    if (u == goal)
      throw FoundGoal{};
  }
};

struct OctileHeuristic : boost::astar_heuristic<ImplicitGrid, std::uint64_t> {
  const PlanningGrid* grid;
  Cell goal;
  OctileHeuristic(const PlanningGrid* g, Cell t) : grid(g), goal(t) {}
  std::uint64_t operator()(std::uint32_t v) const { return octileCost(grid->cellOf(v), goal); }
};

// Dense maps for boost, allocated once per grid.
struct BoostWorkspace {
  std::vector<std::uint32_t> predecessor;
  std::vector<std::uint64_t> distance;
  std::vector<std::uint64_t> rank;
  std::vector<boost::default_color_type> color;
  explicit BoostWorkspace(std::size_t n) : predecessor(n), distance(n), rank(n), color(n) {}
};

std::uint64_t boostAStar(const PlanningGrid& grid, BoostWorkspace& ws, const Cell& s,
                         const Cell& t) {
  const ImplicitGrid g{&grid};
  const auto start = static_cast<std::uint32_t>(grid.index(s));
  const auto goal = static_cast<std::uint32_t>(grid.index(t));
  const auto weight = boost::make_function_property_map<GridEdge, std::uint64_t>(
      [](const GridEdge& e) { return e.diagonal ? kDiagonalCost : kStraightCost; });
  const boost::typed_identity_property_map<std::uint32_t> index;
  try {
    boost::astar_search(
        g, start, OctileHeuristic(&grid, t),
        boost::weight_map(weight)
            .vertex_index_map(index)
            .predecessor_map(boost::make_iterator_property_map(ws.predecessor.begin(), index))
            .distance_map(boost::make_iterator_property_map(ws.distance.begin(), index))
            .rank_map(boost::make_iterator_property_map(ws.rank.begin(), index))
            .color_map(boost::make_iterator_property_map(ws.color.begin(), index))
            .visitor(GoalVisitor(goal)));
  } catch (const FoundGoal&) {
    return ws.distance[goal];
  }
  return std::numeric_limits<std::uint64_t>::max();
}

// ---- Maps ----------------------------------------------------------------------------------

PlanningGrid randomRectangles(int n, std::uint64_t seed) {
  PlanningGrid grid = PlanningGrid::freeGrid(n, n, 0.01);
  std::mt19937_64 rng(seed);
  const int max_side = std::max(2, n / 50);
  std::uniform_int_distribution<int> pos(0, n - 1), side(1, max_side);
  const auto target = static_cast<std::size_t>(0.2 * static_cast<double>(grid.cellCount()));
  std::size_t blocked = 0;
  while (blocked < target) {
    const int c0 = pos(rng), r0 = pos(rng), w = side(rng), h = side(rng);
    for (int r = r0; r < std::min(n, r0 + h); ++r)
      for (int c = c0; c < std::min(n, c0 + w); ++c) {
        std::uint8_t& b = grid.blocked[grid.index({c, r})];
        blocked += b == 0 ? 1 : 0;
        b = 1;
      }
  }
  for (int r = 0; r < 8; ++r)
    for (int c = 0; c < 8; ++c) {
      grid.setBlocked({c, r}, false);
      grid.setBlocked({n - 1 - c, n - 1 - r}, false);
    }
  return grid;
}

struct Case {
  PlanningGrid grid;
  Cell start, goal;
  std::uint64_t cost = 0;
  std::uint64_t expansions = 0;
  std::unique_ptr<AStarPlanner> planner = std::make_unique<AStarPlanner>();
  std::unique_ptr<BoostWorkspace> boost;
  bool checked = false;
  std::string error;
};

Case& caseFor(int n) {
  static std::map<int, Case> cases;
  auto it = cases.find(n);
  if (it != cases.end())
    return it->second;
  Case& c = cases[n];
  c.start = {0, 0};
  c.goal = {n - 1, n - 1};
  for (std::uint64_t seed = 1;; ++seed) {
    c.grid = randomRectangles(n, seed);
    const PlanResult r = c.planner->plan(c.grid, c.start, c.goal);
    if (r.found()) {
      c.cost = r.cost;
      c.expansions = r.expansions;
      break;
    }
  }
  c.boost = std::make_unique<BoostWorkspace>(c.grid.cellCount());
  const std::uint64_t boost_cost = boostAStar(c.grid, *c.boost, c.start, c.goal);
  if (boost_cost != c.cost)
    c.error = "boost and AStarPlanner costs differ";
  return c;
}

void BM_AStarOurs(benchmark::State& state) {
  Case& c = caseFor(static_cast<int>(state.range(0)));
  if (!c.error.empty()) {
    state.SkipWithError(c.error.c_str());
    return;
  }
  for (auto _ : state) {
    const PlanResult r = c.planner->plan(c.grid, c.start, c.goal);
    if (r.cost != c.cost)
      state.SkipWithError("cost changed");
    benchmark::DoNotOptimize(r.cells.data());
  }
  state.counters["expansions"] = static_cast<double>(c.expansions);
  state.counters["cost_m"] = static_cast<double>(c.cost) / kStraightCost * c.grid.resolution_m;
}

// The same planner with jump points off (every free neighbour queued, as boost does): shows what
// the data layout alone gives and what jump point search adds.
void BM_AStarOursPlain(benchmark::State& state) {
  Case& c = caseFor(static_cast<int>(state.range(0)));
  if (!c.error.empty()) {
    state.SkipWithError(c.error.c_str());
    return;
  }
  AStarOptions options;
  options.mode = SearchMode::kPlain;
  std::uint64_t expansions = 0;
  for (auto _ : state) {
    const PlanResult r = c.planner->plan(c.grid, c.start, c.goal, options);
    if (r.cost != c.cost)
      state.SkipWithError("plain A* cost differs");
    expansions = r.expansions;
    benchmark::DoNotOptimize(r.cells.data());
  }
  state.counters["expansions"] = static_cast<double>(expansions);
}

void BM_AStarBoost(benchmark::State& state) {
  Case& c = caseFor(static_cast<int>(state.range(0)));
  if (!c.error.empty()) {
    state.SkipWithError(c.error.c_str());
    return;
  }
  for (auto _ : state) {
    const std::uint64_t cost = boostAStar(c.grid, *c.boost, c.start, c.goal);
    if (cost != c.cost)
      state.SkipWithError("cost changed");
    benchmark::DoNotOptimize(cost);
  }
  state.counters["cost_m"] = static_cast<double>(c.cost) / kStraightCost * c.grid.resolution_m;
}

BENCHMARK(BM_AStarOurs)->Arg(500)->Arg(2000)->Arg(5000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AStarOursPlain)->Arg(500)->Arg(2000)->Arg(5000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AStarBoost)->Arg(500)->Arg(2000)->Arg(5000)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace irgs::bench

BENCHMARK_MAIN();
