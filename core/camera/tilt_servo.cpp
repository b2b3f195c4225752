#include "core/camera/tilt_servo.hpp"

#include <algorithm>
#include <stdexcept>

namespace irgs {

double TiltLaw::tiltFor(double distance_m) const {
  if (!(near_m < far_m))
    throw std::invalid_argument("TiltLaw: near_m must be below far_m");
  const double s = std::clamp((distance_m - near_m) / (far_m - near_m), 0.0, 1.0);
  return max_tilt_rad + s * (min_tilt_rad - max_tilt_rad);
}

double TiltLaw::distanceFor(double tilt_rad) const {
  if (!(near_m < far_m) || max_tilt_rad == min_tilt_rad)
    throw std::invalid_argument("TiltLaw: degenerate law");
  const double s = std::clamp((tilt_rad - max_tilt_rad) / (min_tilt_rad - max_tilt_rad), 0.0, 1.0);
  return near_m + s * (far_m - near_m);
}

TiltServo::TiltServo(double initial_rad, double max_rate_radps)
    : angle_rad_(initial_rad), max_rate_radps_(max_rate_radps) {
  if (!(max_rate_radps > 0.0))
    throw std::invalid_argument("TiltServo: the rate must be positive");
}

double TiltServo::step(double command_rad, double dt_s) {
  const double max_step = max_rate_radps_ * std::max(dt_s, 0.0);
  angle_rad_ += std::clamp(command_rad - angle_rad_, -max_step, max_step);
  return angle_rad_;
}

}  // namespace irgs
