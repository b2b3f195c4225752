#include "core/camera/ceiling_scene.hpp"

#include <algorithm>
#include <cmath>

namespace irgs {

bool CeilingRect::contains(const Vec2& p) const {
  const double c = std::cos(heading_rad), s = std::sin(heading_rad);
  const Vec2 d = p - centre;
  return std::abs(c * d.x() + s * d.y()) <= 0.5 * length_m &&
         std::abs(-s * d.x() + c * d.y()) <= 0.5 * width_m;
}

double CeilingRect::distance(const Vec2& p) const {
  const double c = std::cos(heading_rad), s = std::sin(heading_rad);
  const Vec2 d = p - centre;
  const double ex = std::max(std::abs(c * d.x() + s * d.y()) - 0.5 * length_m, 0.0);
  const double ey = std::max(std::abs(-s * d.x() + c * d.y()) - 0.5 * width_m, 0.0);
  return std::hypot(ex, ey);
}

std::vector<Vec2> CeilingRect::corners() const {
  const Vec2 u(std::cos(heading_rad), std::sin(heading_rad));
  const Vec2 v(-u.y(), u.x());
  const Vec2 a = 0.5 * length_m * u, b = 0.5 * width_m * v;
  return {centre - a - b, centre + a - b, centre + a + b, centre - a + b};
}

CeilingRect lightRect(const CeilingLight& light) {
  const Vec2 d = light.tube.b - light.tube.a;
  return {0.5 * (light.tube.a + light.tube.b), std::atan2(d.y(), d.x()), d.norm(), light.width_m};
}

CeilingScene sceneFromMap(const WorldMap& map, double ceiling_height_m) {
  CeilingScene scene;
  scene.ceiling_height_m = ceiling_height_m > 0.0 ? ceiling_height_m : map.ceiling_height_m;
  for (const CeilingMarker& m : map.markers) {
    const CeilingRect rect{m.position, m.heading_rad, m.size_m, m.size_m};
    if (m.colour == kDefaultMarkerColour) {
      scene.markers.push_back(rect);
    } else {  // painted in its own colour: not a marker the detector is meant to find
      scene.decorations.push_back(
          {rect, Albedo{m.colour.r / 255.0, m.colour.g / 255.0, m.colour.b / 255.0}});
    }
  }
  for (const CeilingLight& l : map.lights)
    scene.lights.push_back(lightRect(l));
  return scene;
}

}  // namespace irgs
