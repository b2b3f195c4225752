#pragma once
// Where a scripted moving obstacle (world_map.hpp) is at a given time along its path.

#include <vector>

#include "core/world/world_map.hpp"

namespace irgs {

// Length of the obstacle's path in metres (with the closing leg when it loops).
double movingObstaclePathLength(const MovingObstacle& obstacle);

// Origin of the obstacle after travelling `distance_m` along its path (wrapped when it loops,
// clamped at the last point otherwise). Negative distances give path[0].
Vec2 movingObstacleAt(const MovingObstacle& obstacle, double distance_m);

// Origin of the obstacle at `time_s` when it never waits: start_delay_s, then speed_mps.
Vec2 movingObstaclePosition(const MovingObstacle& obstacle, double time_s);

// The obstacle's polygon in the world frame with its origin at `origin`.
std::vector<Vec2> movingObstaclePolygon(const MovingObstacle& obstacle, const Vec2& origin);

}  // namespace irgs
