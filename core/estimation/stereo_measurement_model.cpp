#include "core/estimation/stereo_measurement_model.hpp"

#include <cmath>

namespace irgs {

namespace {

// Shared by (46) for walls and points: d d^ / d Phi for a reflector direction phi.
double headingDerivative(const LocState& x, const SensorMount& mount, double phi) {
  const double a = x(kLocPhi) - phi;
  return mount.x_m * std::sin(a) + mount.y_m * std::cos(a);
}

}  // namespace

Pose2 sensorWorldPose(const LocState& x, const SensorMount& mount) {
  const double c = std::cos(x(kLocPhi)), s = std::sin(x(kLocPhi));
  // (13) x_T = x + x'_T cos(Phi) - y'_T sin(Phi)
  // (14) y_T = y + x'_T sin(Phi) + y'_T cos(Phi)   [A000-1: printed -y'_T cos(Phi)]
  // (15) phi_T = Phi + phi'_T
  return {x(kLocX) + mount.x_m * c - mount.y_m * s, x(kLocY) + mount.x_m * s + mount.y_m * c,
          wrapAngle(x(kLocPhi) + mount.phi_rad)};
}

ScalarPrediction predictWallDistance(const LocState& x, const SensorMount& mount,
                                     const FacingLine& wall) {
  const Pose2 t = sensorWorldPose(x, mount);
  const double c = std::cos(wall.phi_eff_rad), s = std::sin(wall.phi_eff_rad);
  ScalarPrediction out;
  // (17) d^ = P_v (P_R - x_T cos(phi) - y_T sin(phi)) = P_eff - x_T cos(phi_eff) - y_T sin(...)
  out.value = wall.p_eff_m - t.x * c - t.y * s;
  // (46) grad_d, third entry per A000-1, P_v folded in by the robot-facing form (A000-3/A000-9)
  out.jacobian << -c, -s, headingDerivative(x, mount, wall.phi_eff_rad);
  return out;
}

ScalarPrediction predictWallBearing(const LocState& x, const SensorMount& mount,
                                    const FacingLine& wall) {
  ScalarPrediction out;
  // (16) theta^ = phi - Phi^ - phi'_T  (phi_eff per A000-9)
  out.value = wrapAngle(wall.phi_eff_rad - x(kLocPhi) - mount.phi_rad);
  // (47) grad_theta = [0, 0, -1]
  out.jacobian << 0.0, 0.0, -1.0;
  return out;
}

ScalarPrediction predictPointDistance(const LocState& x, const SensorMount& mount, const Vec2& p) {
  const Pose2 t = sensorWorldPose(x, mount);
  const Vec2 delta = p - t.position();
  ScalarPrediction out;
  // (18)/(19) d^ = sqrt((x_c - x_T)^2 + (y_c - y_T)^2)
  out.value = delta.norm();
  if (!(out.value > 0.0))
    return out;
  const double phi = std::atan2(delta.y(), delta.x());
  // (46) with phi = bearing T -> C (A000-3)
  out.jacobian << -delta.x() / out.value, -delta.y() / out.value, headingDerivative(x, mount, phi);
  return out;
}

}  // namespace irgs
