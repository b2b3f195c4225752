#pragma once
// What the three-caster steer/drive robot of paper 000 reports from its six encoders: per caster
// the drive wheel's rotation and the steering axis' angle relative to the body, both as
// cumulative counts (DriveGeometry::ticksPerWheelRad() counts per radian). A value type shared
// by the simulator (core/sim/caster_drive_sim.hpp), TelemetrySample and the caster EKF.
//
// Steering counts are absolute: 0 = the wheel trailing straight behind its axis with the robot
// moving forward (phi_i = 0 in (26)). Drive counts start at 0; two samples' difference is the
// interval's DeltaTheta (a consumer that sees only some samples still gets every count).

#include <array>
#include <cstdint>

namespace irgs {

struct CasterEncoders {
  std::array<std::int64_t, 3> drive_ticks{};     // theta_i, cumulative
  std::array<std::int64_t, 3> steering_ticks{};  // phi_i, absolute
  friend bool operator==(const CasterEncoders&, const CasterEncoders&) = default;
};

}  // namespace irgs
