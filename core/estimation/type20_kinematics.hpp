#pragma once
// Kinematics of the Type (2,0) robot of paper 004 (digest 5.5): two fixed wheels 1f, 2f on a
// common axle at +-L from the centre and a castor 3c (distance L, offset d), inputs
// eta = (eta1, eta2) = (forward speed v, turn rate omega): a differential drive (degree of
// mobility 2, steerability 0). Configuration q = (x, y, theta, beta3, psi1, psi2, psi3).
//
// (21) qdot = S(q) eta with the corrections A004-3 (castor no-slip row d + L sin(beta)) and
// A004-4 (rows 2-3 of S(q)), re-derived from the constraints J1 R(theta) xidot + J2 psidot = 0 and
// C1 R(theta) xidot + C2 beta3dot = 0 (a unit test checks them with the paper's (16)-(19)).
// Pose rates are in the project frame (theta = forward heading = theta_004 + pi/2, A004-1);
// wheel angles psi_i and the castor angle beta3 keep the paper's (Campion) sign convention.

#include "core/geometry/types.hpp"

namespace irgs {

struct Type20Geometry {
  double half_axle_m = 0.12;      // L: each fixed wheel's distance from the centre
  double wheel_radius_m = 0.03;   // r (all three wheels, as (17) J2 = r I)
  double castor_offset_m = 0.02;  // d: castor steering axis to its wheel contact
};

// Throws std::invalid_argument unless L, r, d are finite and > 0.
void validate(const Type20Geometry& geometry);

struct Type20Rates {
  double x_mps = 0.0;  // world frame
  double y_mps = 0.0;
  double theta_radps = 0.0;
  double beta3_radps = 0.0;  // castor orientation rate
  double psi1_radps = 0.0;   // wheel 1f (alpha = 0)
  double psi2_radps = 0.0;   // wheel 2f (alpha = pi)
  double psi3_radps = 0.0;   // castor wheel
};

// qdot = S(q) eta at heading theta (project frame) and castor angle beta3.
Type20Rates type20Rates(const Type20Geometry& geometry, double theta_rad, double beta3_rad,
                        double v_mps, double omega_radps);

}  // namespace irgs
