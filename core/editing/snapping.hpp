#pragma once
// Snapping of points the user places: to existing endpoints and vertices, to a fixed angle step
// from the previous point (15/45/90 degrees), and to the grid. World metres and radians.
//
// Priority: an endpoint within its radius wins (joining walls exactly matters most); else, when
// an anchor (the previous point) is given and angle snapping is on, the direction from the anchor
// is rounded to the angle step and the length to the grid step; else the grid.

#include <optional>
#include <vector>

#include "core/editing/map_edit.hpp"
#include "core/geometry/types.hpp"
#include "core/world/world_map.hpp"

namespace irgs::editing {

struct SnapSettings {
  bool grid = true;
  double grid_step_m = 0.1;  // > 0
  bool endpoints = true;
  double endpoint_radius_m = 0.1;  // >= 0; the GUI derives it from a pixel radius
  double angle_step_rad = 0.0;     // 0 = off; otherwise e.g. 15, 45 or 90 degrees
};

enum class SnapKind { kNone, kGrid, kEndpoint, kAngle };

struct SnapResult {
  Vec2 point = Vec2::Zero();
  SnapKind kind = SnapKind::kNone;
};

// Throws std::invalid_argument for a non-positive or non-finite grid step, a negative radius or
// a negative / non-finite angle step. A non-finite raw point is returned unchanged (kNone).
SnapResult snapPoint(const Vec2& raw, const SnapSettings& settings,
                     const std::vector<Vec2>& targets,
                     const std::optional<Vec2>& anchor = std::nullopt);

// Every point worth snapping to: wall points, obstacle vertices, features, the start position,
// marker centres, light ends and midpoints, graph nodes;
// elements in `exclude` are left out (the ones being moved).
std::vector<Vec2> snapTargets(const WorldMap& map, const std::vector<ElementRef>& exclude = {});

// Rounds to the nearest multiple of step (step > 0).
double roundToStep(double value, double step);

}  // namespace irgs::editing
