#pragma once
// What the robot-side motion primitives know of the robot: its sonar mounts, its motion limits
// and the reach of its body. Fixed size, filled once at start-up (from a RobotProfile on the
// host, motion_geometry_profile.hpp; from the firmware's own tables on a microcontroller).

#include <array>
#include <cstdint>

#include "core/geometry/types.hpp"

namespace irgs::motion {

inline constexpr std::size_t kMaxSonars = 32;

struct SonarMount {
  Pose2 mount;  // body frame
  double half_beam_rad = degToRad(12.5);
  double max_range_m = 4.0;
};

struct MotionGeometry {
  std::array<SonarMount, kMaxSonars> sonars{};
  std::uint8_t sonar_count = 0;
  double max_speed_mps = 0.4;
  double max_turn_rate_radps = 1.5;
  double max_accel_mps2 = 0.8;
  double max_turn_accel_radps2 = 4.0;
  double front_extent_m = 0.15;  // body outline ahead of the origin
  double body_radius_m = 0.2;    // smallest circle about the origin holding the body
};

// The sonar roles a wall-following robot needs, found from the mounts. Missing roles stay -1.
struct SonarRoles {
  // Forward-looking (|heading| <= 20 deg) sonars, all of them.
  std::array<std::int8_t, kMaxSonars> forward{};
  std::uint8_t forward_count = 0;
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
    return (wall_on_left ? left : right).front >= 0 && forward_count > 0;
  }
  const SidePair& side(bool wall_on_left) const { return wall_on_left ? left : right; }
};

SonarRoles findSonarRoles(const MotionGeometry& geometry);

}  // namespace irgs::motion
