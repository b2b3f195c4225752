#pragma once
// The sonar roles a wall-following robot needs (front pair, side pairs), found from the robot
// profile's mounts, and the latest reading of every sonar. Readings older than max_age_s or
// beyond the valid distance (position revision (d)) count as "no wall".

#include <optional>
#include <vector>

#include "core/robot/robot_profile.hpp"
#include "core/robot/telemetry.hpp"

namespace irgs {

struct SonarRoles {
  // Forward-looking (|heading| <= 20 deg) sonars, all of them.
  std::vector<int> forward;
  // The forward pair at (nearly) the same x with the widest lateral baseline (revision (a)).
  int front_left = -1;
  int front_right = -1;
  double front_baseline_m = 0.0;
  // Side pairs (heading +-90 deg +-20), front and rear with the widest x baseline (revision (c)).
  struct SidePair {
    int front = -1;
    int rear = -1;
    double baseline_m = 0.0;
    bool valid() const { return front >= 0 && rear >= 0 && baseline_m > 0.0; }
  };
  SidePair left;
  SidePair right;

  bool canFollow(bool wall_on_left) const {
    return (wall_on_left ? left : right).front >= 0 && !forward.empty();
  }
};

// Finds the roles from the mounts. Missing roles stay -1.
SonarRoles findSonarRoles(const RobotProfile& profile);

class SonarView {
 public:
  SonarView(const RobotProfile& profile, double valid_distance_m, double max_age_s = 0.35);

  void update(const TelemetrySample& sample);
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
  const RobotProfile& profile() const { return profile_; }
  double validDistance_m() const { return valid_distance_m_; }

 private:
  struct Last {
    double time_s = -1e9;
    double range_m = 0.0;
    bool echo = false;
  };
  RobotProfile profile_;
  SonarRoles roles_;
  std::vector<Last> last_;
  double valid_distance_m_;
  double max_age_s_;
  double now_s_ = 0.0;
  double min_time_s_ = -1e9;
};

}  // namespace irgs
