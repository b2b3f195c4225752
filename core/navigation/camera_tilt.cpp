#include "core/navigation/camera_tilt.hpp"

#include <algorithm>

namespace irgs {

double tiltRise(const TiltLaw& law, double tilt_rad) {
  const double span = law.max_tilt_rad - law.min_tilt_rad;
  if (!(span > 0.0))
    return 0.0;
  return std::clamp((tilt_rad - law.min_tilt_rad) / span, 0.0, 1.0);
}

}  // namespace irgs
