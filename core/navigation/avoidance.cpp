#include "core/navigation/avoidance.hpp"

#include <algorithm>

namespace irgs {

double repulsionWeight(const AvoidanceParams& params, double range_m) {
  if (!(params.influence_m > 0.0))
    return 0.0;
  return std::max(0.0, (params.influence_m - std::max(range_m, 0.0)) / params.influence_m);
}

Vec2 repulsiveSum(const AvoidanceParams& params, std::span<const SonarRay> rays) {
  Vec2 sum = Vec2::Zero();
  for (const SonarRay& r : rays)
    sum += repulsionWeight(params, r.range_m) * r.direction;
  return -params.k_rep * sum;
}

Vec2 moveVector(const AvoidanceParams& params, const Vec2& target_body, const Vec2& repulsive) {
  const double n = target_body.norm();
  const Vec2 target = n > 0.0 ? Vec2(target_body * (params.target_gain / n)) : Vec2::Zero();
  return target + repulsive;
}

}  // namespace irgs
