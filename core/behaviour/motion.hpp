#pragma once
// Motion primitives shared by the behaviours: on-the-spot turns to a heading and straight legs
// with heading hold, on the odometry pose (what the robot believes), SI units.

#include <algorithm>
#include <cmath>

#include "core/geometry/types.hpp"
#include "core/robot/telemetry.hpp"

namespace irgs {

// Angular velocity that turns the robot from heading_rad to target_rad: proportional with a
// floor (so static friction never stalls the last degree) and the rate limit.
inline double turnRate(double heading_rad, double target_rad, double max_rate_radps) {
  const double err = wrapAngle(target_rad - heading_rad);
  const double w = std::clamp(3.0 * err, -max_rate_radps, max_rate_radps);
  const double floor = std::min(0.15, max_rate_radps);
  return std::abs(w) < floor ? std::copysign(floor, err) : w;
}

// True once the heading is within tolerance of the target.
inline bool turnDone(double heading_rad, double target_rad, double tolerance_rad = degToRad(1.0)) {
  return std::abs(wrapAngle(target_rad - heading_rad)) <= tolerance_rad;
}

// Heading hold for a straight leg: a proportional correction toward hold_rad.
inline VelocityCommand straightCommand(double heading_rad, double hold_rad, double speed_mps) {
  return {speed_mps, std::clamp(2.0 * wrapAngle(hold_rad - heading_rad), -0.5, 0.5)};
}

}  // namespace irgs
