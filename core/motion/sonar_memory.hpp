#pragma once
// The latest reading of every sonar, as the motion primitives see them: readings older than
// max_age_s, taken before forgetBefore(), or beyond the valid distance (position revision (d))
// count as "no wall". Fixed size; no heap.

#include <array>
#include <optional>

#include "core/motion/motion_geometry.hpp"
#include "core/motion/motion_input.hpp"

namespace irgs::motion {

class SonarMemory {
 public:
  SonarMemory(const MotionGeometry& geometry, double valid_distance_m, double max_age_s = 0.35);

  // Takes the step's fresh readings (sensors outside the geometry are ignored).
  void update(const MotionInput& input);
  // Ignores every reading taken before time_s (after a turn the old readings look elsewhere).
  void forgetBefore(double time_s) { min_time_s_ = time_s; }
  // True when the last update() carried a reading of this sensor.
  bool updatedNow(int sensor) const;

  // Range from the sonar's face, or nullopt: no echo, stale, or beyond the valid distance.
  std::optional<double> range(int sensor) const;
  // Distance from the body origin along the sensor axis direction, perpendicular for side
  // sonars: range + |lateral mount offset| (side) or + forward mount offset (forward).
  std::optional<double> sideDistance(int sensor) const;
  // Closest obstacle ahead of the body origin over all forward sonars (range + mount x).
  std::optional<double> frontDistance() const;

  const SonarRoles& roles() const { return roles_; }
  const MotionGeometry& geometry() const { return *geometry_; }
  double validDistance_m() const { return valid_distance_m_; }
  void setValidDistance(double valid_distance_m) { valid_distance_m_ = valid_distance_m; }

 private:
  struct Last {
    double time_s = -1e9;
    double range_m = 0.0;
    bool echo = false;
  };
  const MotionGeometry* geometry_;
  SonarRoles roles_;
  std::array<Last, kMaxSonars> last_{};
  double valid_distance_m_;
  double max_age_s_;
  double now_s_ = 0.0;
  double min_time_s_ = -1e9;
};

}  // namespace irgs::motion
