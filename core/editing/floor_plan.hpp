#pragma once
// The floor-plan image's placement in the world and its calibration from two clicked points.
//
// A pixel (u, v) of the image (u right, v down from the top-left corner) lies at
//   world = origin + R(rotation) * s * (u, -v)        (s = metres per pixel)
// (image rows run down, world y up). Two clicked image points A and B with their true world
// positions fix s, the rotation and the origin (a similarity); with only the true distance
// between them, A's world position and the current rotation are kept and s is rescaled.

#include <optional>

#include "core/geometry/types.hpp"
#include "core/world/world_map.hpp"

namespace irgs::editing {

Vec2 floorPlanToWorld(const FloorPlan& plan, const Vec2& pixel);
Vec2 worldToFloorPlan(const FloorPlan& plan, const Vec2& world);

// The plan moved, turned and scaled so that image pixel a lands on world_a and b on world_b.
// Nothing when the two pixels or the two world points (nearly) coincide or a value is not
// finite. Opacity, source and extras are kept.
std::optional<FloorPlan> calibrateFloorPlan(const FloorPlan& plan, const Vec2& pixel_a,
                                            const Vec2& pixel_b, const Vec2& world_a,
                                            const Vec2& world_b);

// The plan rescaled so that pixels a and b are `distance_m` apart, pixel a staying where it is
// now in the world (the rotation is kept). Nothing for coinciding pixels or a distance <= 0.
std::optional<FloorPlan> calibrateFloorPlanByDistance(const FloorPlan& plan, const Vec2& pixel_a,
                                                      const Vec2& pixel_b, double distance_m);

}  // namespace irgs::editing
