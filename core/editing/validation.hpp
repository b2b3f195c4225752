#pragma once
// Checks of a map being edited, as values the editor draws on the canvas:
//   - unclosed outlines: a wall end that stops short of another wall (a gap the robot or the
//     sonar model would leak through; ends on a wall or against an obstacle are joined), and a
//     polyline of three or more points whose two ends touch nothing (an outline never closed);
//   - overlapping features: point features closer than a minimum separation, obstacles whose
//     polygons overlap;
//   - the start pose inside a wall: within the robot radius of a wall piece or obstacle edge, or
//     inside an obstacle;
//   - degenerate elements: zero-length walls, obstacles with (near) zero area, an edge joining a
//     node to itself;
//   - the ceiling and the graph: markers, lights and nodes outside the map (the bounds of walls,
//     obstacles and the raster), repeated marker, light or node ids, a node tied to a missing
//     marker, an edge naming a missing node, a repeated edge, an edge whose given cost is less
//     than the distance between its nodes.
// World metres.

#include <string>
#include <vector>

#include "core/editing/map_edit.hpp"
#include "core/io/diagnostic.hpp"
#include "core/world/world_map.hpp"

namespace irgs::editing {

struct ValidationSettings {
  double join_tolerance_m = 0.005;  // ends closer than this to a wall are joined
  double gap_tolerance_m = 0.3;     // ends within this of a wall (but not joined) are gaps
  double feature_separation_m = 0.05;
  double robot_radius_m = 0.15;  // the start pose needs this clearance
};

enum class IssueKind {
  kUnclosedOutline,
  kOverlappingFeatures,
  kOverlappingObstacles,
  kStartInWall,
  kDegenerateElement,
  kOutsideMap,
  kDuplicateId,
  kMissingMarker,
  kMissingNode,
  kDuplicateEdge,
  kEdgeCostBelowDistance,
};

struct MapIssue {
  IssueKind kind = IssueKind::kUnclosedOutline;
  Severity severity = Severity::kWarning;
  std::vector<ElementRef> elements;  // the elements involved
  Vec2 position = Vec2::Zero();      // where to draw the marker
  std::string message;
};

// Issues in a deterministic order (by kind, then element order). Throws std::invalid_argument
// for negative or non-finite settings.
std::vector<MapIssue> validateMap(const WorldMap& map, const ValidationSettings& settings = {});

}  // namespace irgs::editing
