#include "core/motion/motion_settings.hpp"

#include <algorithm>
#include <cmath>

namespace irgs::motion {

double approachSpeed(double distance, double accel, double min_speed, double max_speed) {
  // 0.7 of the ideal braking speed: latency of one step and the acceleration limit of the
  // drive cannot make the robot overshoot.
  const double brake = std::sqrt(2.0 * accel * std::max(distance, 0.0)) * 0.7;
  return std::clamp(brake, min_speed, max_speed);
}

}  // namespace irgs::motion
