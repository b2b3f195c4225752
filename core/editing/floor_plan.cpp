#include "core/editing/floor_plan.hpp"

#include <cmath>

namespace irgs::editing {
namespace {

constexpr double kMinSpan = 1e-9;

bool finite(const Vec2& p) {
  return std::isfinite(p.x()) && std::isfinite(p.y());
}

Vec2 rotate(const Vec2& p, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return {c * p.x() - s * p.y(), s * p.x() + c * p.y()};
}

// Image pixel -> unrotated, unscaled world direction (rows run down, y runs up).
Vec2 flipped(const Vec2& pixel) {
  return {pixel.x(), -pixel.y()};
}

}  // namespace

Vec2 floorPlanToWorld(const FloorPlan& plan, const Vec2& pixel) {
  return plan.origin + rotate(plan.metres_per_pixel * flipped(pixel), plan.rotation_rad);
}

Vec2 worldToFloorPlan(const FloorPlan& plan, const Vec2& world) {
  const Vec2 d = rotate(world - plan.origin, -plan.rotation_rad) / plan.metres_per_pixel;
  return flipped(d);
}

std::optional<FloorPlan> calibrateFloorPlan(const FloorPlan& plan, const Vec2& pixel_a,
                                            const Vec2& pixel_b, const Vec2& world_a,
                                            const Vec2& world_b) {
  if (!finite(pixel_a) || !finite(pixel_b) || !finite(world_a) || !finite(world_b))
    return std::nullopt;
  const Vec2 image = flipped(pixel_b - pixel_a);
  const Vec2 world = world_b - world_a;
  if (image.norm() < kMinSpan || world.norm() < kMinSpan)
    return std::nullopt;
  FloorPlan out = plan;
  out.metres_per_pixel = world.norm() / image.norm();
  out.rotation_rad = wrapAngle(std::atan2(world.y(), world.x()) - std::atan2(image.y(), image.x()));
  // Pixel a must land on world_a: origin = world_a - R s a'.
  out.origin = world_a - rotate(out.metres_per_pixel * flipped(pixel_a), out.rotation_rad);
  return out;
}

std::optional<FloorPlan> calibrateFloorPlanByDistance(const FloorPlan& plan, const Vec2& pixel_a,
                                                      const Vec2& pixel_b, double distance_m) {
  if (!(std::isfinite(distance_m) && distance_m > 0.0) || !finite(pixel_a) || !finite(pixel_b))
    return std::nullopt;
  const Vec2 image = flipped(pixel_b - pixel_a);
  if (image.norm() < kMinSpan)
    return std::nullopt;
  // B's world point: from A's current world position along the current direction of A -> B.
  const Vec2 world_a = floorPlanToWorld(plan, pixel_a);
  const Vec2 direction = rotate(image.normalized(), plan.rotation_rad);
  return calibrateFloorPlan(plan, pixel_a, pixel_b, world_a, world_a + distance_m * direction);
}

}  // namespace irgs::editing
