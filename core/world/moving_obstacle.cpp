#include "core/world/moving_obstacle.hpp"

#include <algorithm>
#include <cmath>

namespace irgs {

namespace {

// Legs of the path: i -> i + 1, plus last -> first when looping.
std::size_t legCount(const MovingObstacle& o) {
  if (o.path.size() < 2)
    return 0;
  return o.loop ? o.path.size() : o.path.size() - 1;
}

const Vec2& legEnd(const MovingObstacle& o, std::size_t leg) {
  return o.path[(leg + 1) % o.path.size()];
}

}  // namespace

double movingObstaclePathLength(const MovingObstacle& obstacle) {
  double total = 0.0;
  for (std::size_t k = 0; k < legCount(obstacle); ++k)
    total += (legEnd(obstacle, k) - obstacle.path[k]).norm();
  return total;
}

Vec2 movingObstacleAt(const MovingObstacle& obstacle, double distance_m) {
  if (obstacle.path.empty())
    return Vec2::Zero();
  const double total = movingObstaclePathLength(obstacle);
  if (!(total > 0.0) || !(distance_m > 0.0))
    return obstacle.path.front();
  double s = obstacle.loop ? std::fmod(distance_m, total) : std::min(distance_m, total);
  for (std::size_t k = 0; k < legCount(obstacle); ++k) {
    const Vec2& a = obstacle.path[k];
    const Vec2& b = legEnd(obstacle, k);
    const double len = (b - a).norm();
    if (s <= len)
      return len > 0.0 ? Vec2(a + (b - a) * (s / len)) : a;
    s -= len;
  }
  return obstacle.loop ? obstacle.path.front() : obstacle.path.back();
}

Vec2 movingObstaclePosition(const MovingObstacle& obstacle, double time_s) {
  return movingObstacleAt(obstacle, (time_s - obstacle.start_delay_s) * obstacle.speed_mps);
}

std::vector<Vec2> movingObstaclePolygon(const MovingObstacle& obstacle, const Vec2& origin) {
  std::vector<Vec2> out;
  out.reserve(obstacle.polygon.size());
  for (const Vec2& v : obstacle.polygon)
    out.push_back(v + origin);
  return out;
}

}  // namespace irgs
