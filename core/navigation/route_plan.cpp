#include "core/navigation/route_plan.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <queue>

namespace irgs {

const char* markerActionName(MarkerAction action) {
  switch (action) {
    case MarkerAction::kStraight:
      return "straight";
    case MarkerAction::kLeft:
      return "left";
    case MarkerAction::kRight:
      return "right";
    case MarkerAction::kStop:
      return "stop";
  }
  return "?";
}

const char* routeStatusName(RouteStatus status) {
  switch (status) {
    case RouteStatus::kOk:
      return "ok";
    case RouteStatus::kUnknownStart:
      return "unknown start node";
    case RouteStatus::kUnknownGoal:
      return "unknown goal node";
    case RouteStatus::kNoPath:
      return "no path";
  }
  return "?";
}

std::string resolveNodeId(const TopoGraph& graph, const std::string& text) {
  for (const TopoNode& n : graph.nodes) {
    if (n.id == text)
      return n.id;
  }
  if (text.empty() ||
      !std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; }))
    return {};
  const unsigned long k = std::stoul(text);
  return k < graph.nodes.size() ? graph.nodes[k].id : std::string();
}

RoutePlan planRoute(const TopoGraph& graph, const std::string& start_id,
                    const std::string& goal_id) {
  RoutePlan plan;
  std::map<std::string, std::size_t> index;
  for (std::size_t i = 0; i < graph.nodes.size(); ++i)
    index.emplace(graph.nodes[i].id, i);
  const auto s = index.find(start_id);
  const auto g = index.find(goal_id);
  if (s == index.end()) {
    plan.status = RouteStatus::kUnknownStart;
    return plan;
  }
  if (g == index.end()) {
    plan.status = RouteStatus::kUnknownGoal;
    return plan;
  }
  const std::size_t n = graph.nodes.size();
  const auto pos = [&](std::size_t i) { return graph.nodes[i].position; };
  // (neighbour, corridor length) per node.
  std::vector<std::vector<std::pair<std::size_t, double>>> adjacent(n);
  bool chord_admissible = true;
  for (const TopoEdge& e : graph.edges) {
    const auto a = index.find(e.from), b = index.find(e.to);
    if (a == index.end() || b == index.end())
      continue;
    const double chord = (pos(b->second) - pos(a->second)).norm();
    const double length = e.cost_m ? *e.cost_m : chord;
    chord_admissible = chord_admissible && length >= chord;
    adjacent[a->second].emplace_back(b->second, length);
    if (e.bidirectional)
      adjacent[b->second].emplace_back(a->second, length);
  }
  const std::size_t goal = g->second;
  // A given corridor length shorter than its chord would make the straight-line heuristic
  // overestimate; the search then runs without one (Dijkstra) and stays optimal.
  const auto heuristic = [&](std::size_t v) {
    return chord_admissible ? (pos(v) - pos(goal)).norm() : 0.0;
  };
  std::vector<double> cost(n, std::numeric_limits<double>::infinity());
  std::vector<std::size_t> parent(n, n);
  std::vector<bool> closed(n, false);
  using Entry = std::pair<double, std::size_t>;  // f, node; ties to the lower index
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> open;
  cost[s->second] = 0.0;
  open.emplace(heuristic(s->second), s->second);
  while (!open.empty()) {
    const std::size_t u = open.top().second;
    open.pop();
    if (closed[u])
      continue;
    closed[u] = true;
    ++plan.expansions;
    if (u == goal)
      break;
    for (const auto& [v, length] : adjacent[u]) {
      const double c = cost[u] + length;
      if (c < cost[v]) {
        cost[v] = c;
        parent[v] = u;
        open.emplace(c + heuristic(v), v);
      }
    }
  }
  if (!closed[goal]) {
    plan.status = RouteStatus::kNoPath;
    return plan;
  }
  std::vector<std::size_t> order;
  for (std::size_t v = goal; v != n; v = parent[v])
    order.push_back(v);
  std::reverse(order.begin(), order.end());
  plan.status = RouteStatus::kOk;
  plan.length_m = cost[goal];
  for (std::size_t k = 0; k < order.size(); ++k) {
    RouteStep step;
    step.node_id = graph.nodes[order[k]].id;
    step.position = pos(order[k]);
    if (k + 1 == order.size()) {
      step.action = MarkerAction::kStop;
    } else if (k > 0) {
      const Vec2 in = pos(order[k]) - pos(order[k - 1]);
      const Vec2 out = pos(order[k + 1]) - pos(order[k]);
      step.turn_rad = wrapAngle(std::atan2(out.y(), out.x()) - std::atan2(in.y(), in.x()));
      if (std::abs(step.turn_rad) < kMarkerStraightTolerance_rad)
        step.action = MarkerAction::kStraight;
      else
        step.action = step.turn_rad > 0.0 ? MarkerAction::kLeft : MarkerAction::kRight;
    }
    plan.steps.push_back(step);
  }
  return plan;
}

}  // namespace irgs
