#pragma once
// What the three-caster steer/drive robot of paper 000 reports from its six encoders: per caster
// the drive wheel's rotation and the steering axis' angle relative to the body, both as
// cumulative counts (DriveGeometry::ticksPerWheelRad() counts per radian). A value type shared
// by the simulator (core/sim/caster_drive_sim.hpp), TelemetrySample and the caster EKF.
//
// Steering counts are absolute: 0 = the wheel trailing straight behind its axis with the robot
// moving forward (phi_i = 0 in (26)). Drive counts start at 0; two samples' difference is the
// interval's DeltaTheta (a consumer that sees only some samples still gets every count).
//
// The robot's own least-squares (J+) dead reckoning also reports its residuals: the sum of
// ||e||_2 of (35) over its dead-reckoning periods [000: 1 ms] and the number of periods, both
// cumulative like the counts. Two samples' differences give the mean residual per period over
// the interval, which is what the adaptive process noise Q = lambda ||e|| (36) needs: a consumer
// that re-splits coarser samples into periods averages the slip and quantisation out and
// computes a smaller ||e|| (docs/localization.md). residual_periods == 0: not reported.

#include <array>
#include <cstdint>

namespace irgs {

struct CasterEncoders {
  std::array<std::int64_t, 3> drive_ticks{};     // theta_i, cumulative
  std::array<std::int64_t, 3> steering_ticks{};  // phi_i, absolute
  double residual_sum_rad = 0.0;                 // sum of ||e|| over the robot's periods
  std::int64_t residual_periods = 0;             // periods in residual_sum_rad
  friend bool operator==(const CasterEncoders&, const CasterEncoders&) = default;
};

}  // namespace irgs
