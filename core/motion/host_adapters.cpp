#include "core/motion/host_adapters.hpp"

#include <algorithm>

namespace irgs::motion {

MotionGeometry motionGeometryOf(const RobotProfile& profile) {
  MotionGeometry g;
  const std::size_t n = std::min(profile.sonars.size(), kMaxSonars);
  for (std::size_t i = 0; i < n; ++i) {
    const SonarSpec& s = profile.sonars[i];
    g.sonars[i] = {s.mount, 0.5 * s.beam_width_rad, s.max_range_m};
  }
  g.sonar_count = static_cast<std::uint8_t>(n);
  g.max_speed_mps = profile.limits.max_speed_mps;
  g.max_turn_rate_radps = profile.limits.max_turn_rate_radps;
  g.max_accel_mps2 = profile.limits.max_accel_mps2;
  g.max_turn_accel_radps2 = profile.limits.max_turn_accel_radps2;
  g.front_extent_m = 0.0;
  for (const Vec2& v : profile.body_outline)
    g.front_extent_m = std::max(g.front_extent_m, v.x());
  g.body_radius_m = profile.bodyRadius();
  return g;
}

MotionInput motionInputOf(const TelemetrySample& sample) {
  MotionInput in;
  in.time_s = sample.time_s;
  in.odometry = sample.odometry_pose;
  in.measured = sample.measured_velocity;
  for (const SonarReading& r : sample.sonar) {
    if (r.sensor >= 0 && static_cast<std::size_t>(r.sensor) < kMaxSonars)
      in.addSonar(r);
  }
  in.bumpers = sample.bumpers;
  in.stalled = sample.drive_stalled;
  return in;
}

}  // namespace irgs::motion
