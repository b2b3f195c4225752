#pragma once
// Odometry of the three-caster steer/drive robot of paper 000 (digest 1.4, 1.5): each caster i
// has a drive angle theta_i and a steering angle phi_i (relative to the robot body); the six
// encoder increments give the body motion by least squares, and the residual measures how
// inconsistent the wheels are (slip, backlash), which sets the adaptive process noise.

#include <Eigen/Core>
#include <array>

#include "core/estimation/localization_types.hpp"
#include "core/robot/caster_encoders.hpp"

namespace irgs {

// Steering axis of caster i in polar coordinates in the robot frame: (d_i, alpha_i).
struct CasterModule {
  double d_m = 0.0;
  double alpha_rad = 0.0;
};

struct CasterDriveGeometry {
  double wheel_radius_m = 0.0;  // r
  double offset_m = 0.0;        // eps: steering axis to wheel contact, trailing, must be > 0
  std::array<CasterModule, 3> casters{};
};

// Throws std::invalid_argument unless r > 0, eps > 0, all finite.
void validate(const CasterDriveGeometry& geometry);

using CasterVector = Eigen::Matrix<double, 6, 1>;  // (theta_1, phi_1, theta_2, phi_2, ...)
using CasterG = Eigen::Matrix<double, 6, 3>;
using CasterPinv = Eigen::Matrix<double, 3, 6>;
using BodyTwist = Eigen::Matrix<double, 3, 1>;  // (V_ox, V_oy, Omega) in the body frame (22)

// (26) stacked as (29): Thetadot = G Wdot, Wdot the body-frame twist (A000-2).
CasterG casterJacobian(const CasterDriveGeometry& geometry,
                       const std::array<double, 3>& steering_rad);

struct CasterOdometry {
  bool ok = false;                                 // false when G is rank deficient or input bad
  BodyTwist body_delta = BodyTwist::Zero();        // G+ DeltaTheta: (dx, dy, dPhi) body frame
  CasterPinv pseudo_inverse = CasterPinv::Zero();  // G+ = (G'G)^-1 G'
  CasterVector residual = CasterVector::Zero();    // (35) e = (I - G G+) DeltaTheta (A000-6)
  double residual_norm = 0.0;                      // ||e||_2, rad
};

// (33)/(35) in the body frame: J+ = R(Phi) G+ since R is orthogonal, so the least-squares body
// motion and the residual do not depend on the heading.
CasterOdometry casterOdometry(const CasterDriveGeometry& geometry,
                              const std::array<double, 3>& steering_rad,
                              const CasterVector& delta_theta);

// The steering angles (rad) the encoders report: counts / ticks_per_rad.
std::array<double, 3> casterSteering(const CasterEncoders& encoders, double ticks_per_rad);

// J+ odometry of period k (0-based) of `periods` equal periods between the encoder readings
// `from` and `to`, assuming constant encoder rates in between: DeltaTheta = (to - from) /
// periods, evaluated at the steering interpolated to the middle of the period (second-order
// accurate while the casters swivel). periods = 1: one step from the mid steering.
CasterOdometry casterIntervalOdometry(const CasterDriveGeometry& geometry,
                                      const CasterEncoders& from, const CasterEncoders& to,
                                      double ticks_per_rad, int k = 0, int periods = 1);

}  // namespace irgs
