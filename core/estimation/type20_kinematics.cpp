#include "core/estimation/type20_kinematics.hpp"

#include <cmath>
#include <stdexcept>

namespace irgs {

void validate(const Type20Geometry& g) {
  for (double v : {g.half_axle_m, g.wheel_radius_m, g.castor_offset_m}) {
    if (!std::isfinite(v) || !(v > 0.0))
      throw std::invalid_argument("Type20Geometry: L, r and d must be finite and > 0");
  }
}

Type20Rates type20Rates(const Type20Geometry& g, double theta_rad, double beta3_rad, double v_mps,
                        double omega_radps) {
  validate(g);
  const double l = g.half_axle_m, r = g.wheel_radius_m, d = g.castor_offset_m;
  const double sb = std::sin(beta3_rad), cb = std::cos(beta3_rad);
  Type20Rates q;
  // Rows 1-3 (A004-4, project frame): xdot = cos(theta) v, ydot = sin(theta) v, thetadot = omega.
  q.x_mps = std::cos(theta_rad) * v_mps;
  q.y_mps = std::sin(theta_rad) * v_mps;
  q.theta_radps = omega_radps;
  // Row 4 (A004-3): beta3dot = (cos(beta) v - (d + L sin(beta)) omega) / d.
  q.beta3_radps = (cb * v_mps - (d + l * sb) * omega_radps) / d;
  // Rows 5-7: psi1dot = -(v + L omega)/r, psi2dot = (v - L omega)/r,
  // psi3dot = -(sin(beta) v + L cos(beta) omega)/r.
  q.psi1_radps = -(v_mps + l * omega_radps) / r;
  q.psi2_radps = (v_mps - l * omega_radps) / r;
  q.psi3_radps = -(sb * v_mps + l * cb * omega_radps) / r;
  return q;
}

}  // namespace irgs
