#pragma once
// The path-following law of paper 004 (digest 5.6, (22)-(25)) with the Lyapunov choice of
// (25) from the same textbook family, for one control period:
//   (22) sdot  = v cos(theta~) / (1 - c l)
//   (25) omega = c sdot - k2 v l sin(theta~)/theta~ - k3 |v| theta~
// l > 0 left of the path, theta~ = theta - theta_r wrapped, c > 0 for a left turn. The caller
// checks 1 - c l against its singularity threshold before calling.

#include <cmath>

namespace irgs::motion {

struct PathLawOutput {
  double sdot_mps = 0.0;
  double omega_radps = 0.0;  // not clamped
};

inline PathLawOutput pathFollowingLaw(double v_mps, double lateral_m, double heading_error_rad,
                                      double curvature, double k2, double k3) {
  PathLawOutput out;
  out.sdot_mps = v_mps * std::cos(heading_error_rad) / (1.0 - curvature * lateral_m);
  const double e = heading_error_rad;
  const double sinc_e = std::abs(e) < 1e-6 ? 1.0 : std::sin(e) / e;
  out.omega_radps =
      curvature * out.sdot_mps - k2 * v_mps * lateral_m * sinc_e - k3 * std::abs(v_mps) * e;
  return out;
}

}  // namespace irgs::motion
