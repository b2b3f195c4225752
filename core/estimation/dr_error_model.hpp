#pragma once
// The 9-state error model of encoder + gyro dead reckoning, paper 001_… (digest 2.2-2.4), in the
// project frame (A001-2: x forward, y left, heading theta CCW from +x, so the paper's deltaX and
// deltaY rows are swapped and the sines/cosines follow).
//
// Error convention: delta = true - computed everywhere (A001-4). States:
//   dx, dy [m]      position error
//   dpsi [rad]      encoder heading error
//   S_R, S_L [1]    right/left encoder scale-factor errors: true increment = R (1 + S_R)
//   dD [m]          wheelbase error: true wheelbase = D + dD
//   dphi [rad]      gyro heading error
//   dB_s [1]        gyro scale-factor error: true rate = (1 + ... + dB_s) * Omega / dt
//   dB_rb [rad/s]   gyro random bias (A001-7: multiplied by dt per step)

#include <Eigen/Core>
#include <cmath>

namespace irgs {

inline constexpr int kDrStates = 9;
inline constexpr int kDrDx = 0;
inline constexpr int kDrDy = 1;
inline constexpr int kDrDpsi = 2;
inline constexpr int kDrSr = 3;
inline constexpr int kDrSl = 4;
inline constexpr int kDrDd = 5;
inline constexpr int kDrDphi = 6;
inline constexpr int kDrDbs = 7;
inline constexpr int kDrDbrb = 8;

using DrState = Eigen::Matrix<double, kDrStates, 1>;
using DrCov = Eigen::Matrix<double, kDrStates, kDrStates>;
using DrRow = Eigen::Matrix<double, 1, kDrStates>;

// One step's inputs to the error model: computed (already corrected) encoder increments R, L [m],
// the heading psi [rad] the position increment is resolved along, the wheelbase D [m], the gyro's
// angle increment Omega = rate * dt [rad] the scale-factor error multiplies, and dt [s].
struct DrStepGeometry {
  double right_m = 0.0;
  double left_m = 0.0;
  double psi_rad = 0.0;
  double wheelbase_m = 0.5;
  double omega_rad = 0.0;
  double dt_s = 1.0;
  // false when this step has no gyro reading: the gyro heading then follows the encoder heading
  // increment, so dphi picks up the encoder errors of the step instead of the gyro's.
  bool gyro_valid = true;
};

// (9) F(k), reconstructed per A001-3 from (3), (4), (8) and mapped per A001-2.
inline DrCov drTransition(const DrStepGeometry& g) {
  const double r = g.right_m, l = g.left_m, d = g.wheelbase_m;
  const double c = std::cos(g.psi_rad), s = std::sin(g.psi_rad);
  DrCov f = DrCov::Identity();
  // (3) dx(k+1) = dx + cos(psi) R/2 S_R + cos(psi) L/2 S_L - sin(psi) (R+L)/2 dpsi   [A001-2]
  f(kDrDx, kDrDpsi) = -s * 0.5 * (r + l);
  f(kDrDx, kDrSr) = c * 0.5 * r;
  f(kDrDx, kDrSl) = c * 0.5 * l;
  // (3) dy(k+1) = dy + sin(psi) R/2 S_R + sin(psi) L/2 S_L + cos(psi) (R+L)/2 dpsi
  f(kDrDy, kDrDpsi) = c * 0.5 * (r + l);
  f(kDrDy, kDrSr) = s * 0.5 * r;
  f(kDrDy, kDrSl) = s * 0.5 * l;
  // (3) dpsi(k+1) = dpsi + R/D S_R - L/D S_L + (L-R)/D^2 dD
  f(kDrDpsi, kDrSr) = r / d;
  f(kDrDpsi, kDrSl) = -l / d;
  f(kDrDpsi, kDrDd) = (l - r) / (d * d);
  if (g.gyro_valid) {
    // (8) dphi(k+1) = dphi + Omega dB_s + dt dB_rb   (A001-7)
    f(kDrDphi, kDrDbs) = g.omega_rad;
    f(kDrDphi, kDrDbrb) = g.dt_s;
  } else {
    f(kDrDphi, kDrSr) = r / d;
    f(kDrDphi, kDrSl) = -l / d;
    f(kDrDphi, kDrDd) = (l - r) / (d * d);
  }
  return f;
}

// (10) with the sign of A001-4: Z = psi_enc - phi_gyro = dphi - dpsi, so H = [0 0 -1 0 0 0 1 0 0].
inline DrRow drMeasurementRow() {
  DrRow h = DrRow::Zero();
  h(kDrDpsi) = -1.0;
  h(kDrDphi) = 1.0;
  return h;
}

}  // namespace irgs
