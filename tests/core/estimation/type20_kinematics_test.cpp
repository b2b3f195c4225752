// Type (2,0) robot of paper 004 (digest 5.5): the corrected S(q) satisfies the paper's rolling
// and no-slip constraints (16)-(19) (with A004-3), written in the paper's own frame.

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <stdexcept>

#include "core/estimation/type20_kinematics.hpp"
#include "core/sim/diff_drive.hpp"
#include "core/sim/random.hpp"

namespace irgs {
namespace {

TEST(Type20Kinematics, CorrectedSqSatisfiesThePapersRollingAndNoSlipConstraints) {
  const Type20Geometry g{0.12, 0.03, 0.02};
  const double l = g.half_axle_m, r = g.wheel_radius_m, d = g.castor_offset_m;
  SimRandom rng(4);
  for (int i = 0; i < 100; ++i) {
    const double theta = 3.0 * rng.gaussian(), beta = 3.0 * rng.gaussian();
    const double v = rng.gaussian(), omega = rng.gaussian();
    const Type20Rates q = type20Rates(g, theta, beta, v, omega);
    // Paper frame: theta_004 = theta - pi/2 (A004-1); R(theta) maps world rates to the robot
    // frame (x lateral, y forward).
    const double t4 = theta - kPi / 2;
    Eigen::Matrix3d rot;
    rot << std::cos(t4), std::sin(t4), 0.0, -std::sin(t4), std::cos(t4), 0.0, 0.0, 0.0, 1.0;
    const Eigen::Vector3d body = rot * Eigen::Vector3d(q.x_mps, q.y_mps, q.theta_radps);
    const double sb = std::sin(beta), cb = std::cos(beta);
    Eigen::Matrix3d j1, c1;
    j1 << 0.0, 1.0, l, 0.0, -1.0, l, cb, sb, l * cb;           // (16)
    c1 << 1.0, 0.0, 0.0, -1.0, 0.0, 0.0, sb, -cb, d + l * sb;  // (18) with A004-3
    const Eigen::Vector3d psi(q.psi1_radps, q.psi2_radps, q.psi3_radps);
    const Eigen::Vector3d rolling = j1 * body + r * psi;  // (17) J2 = r I
    const Eigen::Vector3d no_slip = c1 * body + Eigen::Vector3d(0.0, 0.0, d) * q.beta3_radps;
    EXPECT_LT(rolling.norm(), 1e-12);
    EXPECT_LT(no_slip.norm(), 1e-12);
  }
}

TEST(Type20Kinematics, FixedWheelsTurnAsADifferentialDriveWithWheelbaseTwoL) {
  const Type20Geometry g{0.12, 0.03, 0.02};
  const Type20Rates q = type20Rates(g, 0.3, 0.0, 0.25, 0.8);
  const WheelSpeeds ws = wheelSpeeds(0.25, 0.8, 2.0 * g.half_axle_m);
  // Wheel 1f (alpha = 0) is the right wheel with its axis pointing right: psi1 = -v_R / r.
  EXPECT_NEAR(-q.psi1_radps * g.wheel_radius_m, ws.right_mps, 1e-12);
  EXPECT_NEAR(q.psi2_radps * g.wheel_radius_m, ws.left_mps, 1e-12);
  EXPECT_NEAR(q.x_mps, 0.25 * std::cos(0.3), 1e-12);
  EXPECT_NEAR(q.y_mps, 0.25 * std::sin(0.3), 1e-12);
}

TEST(Type20Kinematics, RejectsANonPositiveCastorOffset) {
  EXPECT_THROW(type20Rates({0.12, 0.03, 0.0}, 0.0, 0.0, 0.1, 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace irgs
