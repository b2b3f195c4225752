#pragma once
// The planning overlay of the map canvas: the raw A* path beside the amended one with its
// numbered turning points and the goal, a coverage path with its region, the position indices
// of map building and the turning points already reached. Plain data plus one paint function;
// world metres in, drawn through the canvas's MapView.

#include <QPointF>
#include <QRectF>
#include <optional>
#include <vector>

#include "core/geometry/types.hpp"
#include "widgets/canvas/map_view.hpp"

class QPainter;

namespace irgs::widgets {

struct PlanningOverlay {
  std::vector<irgs::Vec2> raw_path;      // A* path (turning points), drawn thin and dashed
  std::vector<irgs::Vec2> amended_path;  // the path the robot drives, numbered turning points
  std::optional<irgs::Vec2> goal;
  std::vector<irgs::Vec2> coverage_path;  // lanes of a coverage run
  std::optional<irgs::Box2> region;       // the selected coverage region
  std::vector<irgs::Vec2> indices;        // map-building position indices, numbered from 1
  std::size_t reached = 0;                // turning points of amended/coverage path reached

  bool empty() const {
    return raw_path.empty() && amended_path.empty() && !goal && coverage_path.empty() && !region &&
           indices.empty();
  }
};

// Draws the overlay. Non-finite points are skipped.
void paintPlanningOverlay(QPainter& p, const MapView& view, const PlanningOverlay& overlay);

// The rectangle being dragged out for a region (widget pixels), with its size in metres.
void paintRegionRubberBand(QPainter& p, const MapView& view, const irgs::Vec2& a,
                           const irgs::Vec2& b);

}  // namespace irgs::widgets
