#include "core/sim/body_clearance.hpp"

namespace irgs {

double bodyClearance(const SimWorld& world, std::span<const Vec2> body_world, double cap_m,
                     double tolerance_m) {
  if (body_world.empty())
    return cap_m;
  if (world.polygonTouches(body_world))
    return 0.0;
  const auto within = [&](double d) {
    for (std::size_t i = 0; i < body_world.size(); ++i) {
      if (world.segmentWithin(body_world[i], body_world[(i + 1) % body_world.size()], d))
        return true;
    }
    return false;
  };
  if (!within(cap_m))
    return cap_m;
  // Bisection on the distance: within(lo) is false, within(hi) is true.
  double lo = 0.0, hi = cap_m;
  while (hi - lo > tolerance_m) {
    const double mid = 0.5 * (lo + hi);
    (within(mid) ? hi : lo) = mid;
  }
  return lo;
}

}  // namespace irgs
