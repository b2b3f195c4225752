#pragma once
// Ground-truth clearance of the robot's body: the distance from the body outline to the nearest
// geometry the simulator knows (walls, obstacles, raster, moving obstacles), for run metrics.

#include <span>

#include "core/sim/sim_world.hpp"

namespace irgs {

// Distance from the closed polygon `body_world` (world frame) to the nearest geometry, up to
// cap_m (returned when nothing is closer), to within tolerance_m; 0 when the body touches.
double bodyClearance(const SimWorld& world, std::span<const Vec2> body_world, double cap_m,
                     double tolerance_m = 0.002);

}  // namespace irgs
