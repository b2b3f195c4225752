#pragma once
// Global planning on the topological graph (002_… 3.6, Fig. 15): A* from a start node to a goal
// node, edge cost = corridor length (the edge's cost_m when the map gives it, else the straight
// distance between the two nodes, A002 "edge cost not specified"), then the action the robot
// performs at each marker on the route.

#include <string>
#include <vector>

#include "core/world/world_map.hpp"

namespace irgs {

enum class MarkerAction { kStraight, kLeft, kRight, kStop };
const char* markerActionName(MarkerAction action);

enum class RouteStatus { kOk, kUnknownStart, kUnknownGoal, kNoPath };
const char* routeStatusName(RouteStatus status);

struct RouteStep {
  std::string node_id;
  Vec2 position = Vec2::Zero();
  MarkerAction action = MarkerAction::kStraight;
  // Heading change at this node (outgoing edge direction - incoming), radians CCW; 0 at the
  // start and the goal.
  double turn_rad = 0.0;
};

struct RoutePlan {
  RouteStatus status = RouteStatus::kNoPath;
  std::vector<RouteStep> steps;  // start first, goal last (the goal's action is kStop)
  double length_m = 0.0;
  int expansions = 0;
};

// A turn smaller than this (either way) is "straight" at a marker.
inline constexpr double kMarkerStraightTolerance_rad = 0.5235987755982988;  // 30 deg

// A* with the straight-line heuristic (admissible while every edge costs at least its chord; with
// a given cost below its chord the search runs without a heuristic). Edges
// marked bidirectional = false are travelled from -> to only. start == goal gives a one-step
// route whose action is kStop.
RoutePlan planRoute(const TopoGraph& graph, const std::string& start_id,
                    const std::string& goal_id);

// Node id given as written, or (convenience for the command line) a number k naming the k-th
// node when no node has that id. Empty when neither exists.
std::string resolveNodeId(const TopoGraph& graph, const std::string& text);

}  // namespace irgs
