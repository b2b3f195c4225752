#include "core/planning/traveling.hpp"

#include <cmath>
#include <stdexcept>

#include "core/planning/path_amendment.hpp"

namespace irgs {

TravelPlan makeTravelPlan(const std::vector<Vec2>& points, double initial_heading_rad,
                          double quantum_rad) {
  if (!std::isfinite(initial_heading_rad) || !std::isfinite(quantum_rad) || quantum_rad < 0.0)
    throw std::invalid_argument("makeTravelPlan: heading and quantum must be finite, quantum >= 0");
  for (const Vec2& p : points)
    if (!p.allFinite())
      throw std::invalid_argument("makeTravelPlan: non-finite point");
  const std::vector<Vec2> c = compressPath(points);
  TravelPlan plan;
  double heading = wrapAngle(initial_heading_rad);
  for (std::size_t i = 1; i < c.size(); ++i) {
    TravelSegment s;
    s.from = c[i - 1];
    s.to = c[i];
    const Vec2 d = s.to - s.from;
    const double wanted = std::atan2(d.y(), d.x());
    double turn = wrapAngle(wanted - heading);
    if (quantum_rad > 0.0)
      turn = quantum_rad * std::round(turn / quantum_rad);
    s.turn_rad = turn;
    s.heading_rad = wrapAngle(heading + turn);
    s.distance_m = d.norm();
    s.heading_error_rad = wrapAngle(wanted - s.heading_rad);
    heading = s.heading_rad;
    plan.total_distance_m += s.distance_m;
    plan.turns += std::abs(turn) > kStraightTolerance_rad ? 1 : 0;
    plan.segments.push_back(s);
  }
  return plan;
}

}  // namespace irgs
