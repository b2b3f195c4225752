#include "core/navigation/camera_tilt.hpp"

#include <algorithm>
#include <numbers>

namespace irgs {

double tiltForDistance(const CameraTiltLaw& law, double distance_m) {
  const double span = law.far_distance_m - law.near_distance_m;
  if (!(span > 0.0))
    return distance_m > law.near_distance_m ? law.far_tilt_rad : law.near_tilt_rad;
  const double u = std::clamp((distance_m - law.near_distance_m) / span, 0.0, 1.0);
  return law.near_tilt_rad + u * (law.far_tilt_rad - law.near_tilt_rad);
}

double tiltFromVertical(double tilt_rad) {
  return 0.5 * std::numbers::pi - tilt_rad;
}

double tiltRise(const CameraTiltLaw& law, double tilt_rad) {
  const double span = law.near_tilt_rad - law.far_tilt_rad;
  if (!(span > 0.0))
    return 0.0;
  return std::clamp((tilt_rad - law.far_tilt_rad) / span, 0.0, 1.0);
}

}  // namespace irgs
