#pragma once
// The landmark-navigation overlay of the map canvas (paper 002): the planned route over the
// topological graph (the part already travelled dimmed, the node sought next ringed), the
// navigator's state beside the robot, the repulsive, target and move vectors of the VFH-like
// avoidance drawn from the robot (Fig. 16), and the simulator's moving obstacles. Plain data
// plus one paint function; world metres and radians in.

#include <QString>
#include <optional>
#include <vector>

#include "core/geometry/types.hpp"
#include "widgets/canvas/map_view.hpp"

class QPainter;

namespace irgs::widgets {

struct NavigationOverlay {
  std::vector<irgs::Vec2> route;  // node positions, start first
  int next_node = -1;             // index into route of the node sought, -1: none
  QString state;                  // navigator state, drawn beside the robot
  std::optional<irgs::Pose2> robot;
  // Body-frame vectors (x forward, y left), drawn from the robot scaled by vector_scale_m.
  irgs::Vec2 target = irgs::Vec2::Zero();
  irgs::Vec2 repulsive = irgs::Vec2::Zero();
  irgs::Vec2 move = irgs::Vec2::Zero();
  double vector_scale_m = 1.0;                            // metres drawn per unit of vector length
  std::vector<std::vector<irgs::Vec2>> moving_obstacles;  // world-frame outlines

  bool empty() const { return route.empty() && moving_obstacles.empty(); }
};

void paintNavigationOverlay(QPainter& p, const MapView& view, const NavigationOverlay& overlay);

}  // namespace irgs::widgets
