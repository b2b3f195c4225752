#include "core/editing/snapping.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace irgs::editing {

double roundToStep(double value, double step) {
  return std::round(value / step) * step;
}

SnapResult snapPoint(const Vec2& raw, const SnapSettings& settings,
                     const std::vector<Vec2>& targets, const std::optional<Vec2>& anchor) {
  if (!(settings.grid_step_m > 0.0) || !std::isfinite(settings.grid_step_m))
    throw std::invalid_argument("snap grid step must be a positive number of metres");
  if (!(settings.endpoint_radius_m >= 0.0))
    throw std::invalid_argument("snap endpoint radius must be >= 0");
  if (!(settings.angle_step_rad >= 0.0) || !std::isfinite(settings.angle_step_rad))
    throw std::invalid_argument("snap angle step must be >= 0");
  if (!std::isfinite(raw.x()) || !std::isfinite(raw.y()))
    return {raw, SnapKind::kNone};

  if (settings.endpoints) {
    double best = std::numeric_limits<double>::infinity();
    const Vec2* nearest = nullptr;
    for (const Vec2& t : targets) {
      const double d = (t - raw).norm();
      if (d < best) {
        best = d;
        nearest = &t;
      }
    }
    if (nearest != nullptr && best <= settings.endpoint_radius_m)
      return {*nearest, SnapKind::kEndpoint};
  }

  if (anchor && settings.angle_step_rad > 0.0) {
    const Vec2 d = raw - *anchor;
    const double length = d.norm();
    if (length > 0.0) {
      const double angle = roundToStep(std::atan2(d.y(), d.x()), settings.angle_step_rad);
      double snapped_length = settings.grid ? roundToStep(length, settings.grid_step_m) : length;
      if (snapped_length <= 0.0)
        snapped_length = settings.grid ? settings.grid_step_m : length;
      return {*anchor + snapped_length * Vec2(std::cos(angle), std::sin(angle)), SnapKind::kAngle};
    }
  }

  if (settings.grid) {
    return {Vec2(roundToStep(raw.x(), settings.grid_step_m),
                 roundToStep(raw.y(), settings.grid_step_m)),
            SnapKind::kGrid};
  }
  return {raw, SnapKind::kNone};
}

std::vector<Vec2> snapTargets(const WorldMap& map, const std::vector<ElementRef>& exclude) {
  auto excluded = [&](ElementKind kind, std::size_t index) {
    return std::find(exclude.begin(), exclude.end(), ElementRef{kind, index}) != exclude.end();
  };
  std::vector<Vec2> out;
  for (std::size_t i = 0; i < map.walls.size(); ++i) {
    if (!excluded(ElementKind::kWall, i))
      out.insert(out.end(), map.walls[i].points.begin(), map.walls[i].points.end());
  }
  for (std::size_t i = 0; i < map.obstacles.size(); ++i) {
    if (!excluded(ElementKind::kObstacle, i))
      out.insert(out.end(), map.obstacles[i].polygon.begin(), map.obstacles[i].polygon.end());
  }
  for (std::size_t i = 0; i < map.features.size(); ++i) {
    if (!excluded(ElementKind::kFeature, i))
      out.push_back(map.features[i].position);
  }
  if (!excluded(ElementKind::kStart, 0))
    out.push_back(map.start.position());
  for (std::size_t i = 0; i < map.markers.size(); ++i) {
    if (!excluded(ElementKind::kMarker, i))
      out.push_back(map.markers[i].position);
  }
  for (std::size_t i = 0; i < map.lights.size(); ++i) {
    if (!excluded(ElementKind::kLight, i)) {
      const Segment& t = map.lights[i].tube;
      out.insert(out.end(), {t.a, t.b, Vec2((t.a + t.b) / 2.0)});
    }
  }
  for (std::size_t i = 0; i < map.graph.nodes.size(); ++i) {
    if (!excluded(ElementKind::kNode, i))
      out.push_back(map.graph.nodes[i].position);
  }
  return out;
}

}  // namespace irgs::editing
