#pragma once
// Measurement model of the stereo-sonar EKF (paper 000, digest 1.3 and 1.6): predicted distance
// and bearing of walls, corners and edges from the robot pose, with their Jacobians.

#include "core/estimation/localization_types.hpp"
#include "core/world/wall_model.hpp"

namespace irgs {

struct ScalarPrediction {
  double value = 0.0;
  LocRow jacobian = LocRow::Zero();  // d value / d (x, y, Phi)
};

// (13)-(15) with the A000-1 fix (y'_T to the left):
//   x_T = x + x'_T cos(Phi) - y'_T sin(Phi),  y_T = y + x'_T sin(Phi) + y'_T cos(Phi),
//   phi_T = Phi + phi'_T.
Pose2 sensorWorldPose(const LocState& x, const SensorMount& mount);

// (17) d^ = P_eff - x_T cos(phi_eff) - y_T sin(phi_eff)  (robot-facing form, A000-9), and
// (46) with A000-1/A000-3: grad = [-cos(phi_eff), -sin(phi_eff),
//                                  x'_T sin(Phi - phi_eff) + y'_T cos(Phi - phi_eff)].
ScalarPrediction predictWallDistance(const LocState& x, const SensorMount& mount,
                                     const FacingLine& wall);
// (16) theta^ = phi_eff - Phi - phi'_T (wrapped), (47) grad = [0, 0, -1].
ScalarPrediction predictWallBearing(const LocState& x, const SensorMount& mount,
                                    const FacingLine& wall);
// (18)/(19) d^ = |C - T|; grad as (46) with phi = bearing from T to C (A000-3). At C = T the
// gradient is undefined and returned as zero.
ScalarPrediction predictPointDistance(const LocState& x, const SensorMount& mount, const Vec2& p);

}  // namespace irgs
