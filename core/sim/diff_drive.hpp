#pragma once
// Differential-drive kinematics in the project convention (digest section 6, A003-1):
//   v = (v_R + v_L) / 2,   omega = (v_R - v_L) / B,   B = full wheel separation,
//   v_R = v + omega B / 2,  v_L = v - omega B / 2.

#include <cmath>

#include "core/geometry/types.hpp"

namespace irgs {

struct WheelSpeeds {
  double left_mps = 0.0;
  double right_mps = 0.0;
};

inline WheelSpeeds wheelSpeeds(double v_mps, double omega_radps, double wheelbase_m) {
  return {v_mps - 0.5 * omega_radps * wheelbase_m, v_mps + 0.5 * omega_radps * wheelbase_m};
}

// Moves `pose` along a circular arc of length ds_m (signed, along the heading) turning by
// dtheta_rad. Exact for constant curvature: the chord has length ds * sin(dθ/2) / (dθ/2) and
// points along theta + dθ/2, so a constant (v, omega) traces a circle of radius v / omega.
inline Pose2 integrateArc(const Pose2& pose, double ds_m, double dtheta_rad) {
  const double half = 0.5 * dtheta_rad;
  // sin(x)/x; the series avoids 0/0 and keeps full precision for tiny turns.
  const double sinc = std::abs(half) < 1e-4 ? 1.0 - half * half / 6.0 : std::sin(half) / half;
  const double chord = ds_m * sinc;
  const double heading = pose.theta + half;
  return {pose.x + chord * std::cos(heading), pose.y + chord * std::sin(heading),
          wrapAngle(pose.theta + dtheta_rad)};
}

}  // namespace irgs
