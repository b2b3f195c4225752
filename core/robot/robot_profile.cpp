#include "core/robot/robot_profile.hpp"

#include <algorithm>

namespace irgs {

double RobotProfile::bodyRadius() const {
  // The outline is a polygon, so its farthest point from the origin is a vertex.
  double radius = 0.0;
  for (const Vec2& p : body_outline)
    radius = std::max(radius, p.norm());
  return radius;
}

}  // namespace irgs
