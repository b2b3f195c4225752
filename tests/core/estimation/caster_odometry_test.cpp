#include "core/estimation/caster_odometry.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "core/sim/random.hpp"

namespace irgs {
namespace {

CasterDriveGeometry threeCasters() {
  CasterDriveGeometry g;
  g.wheel_radius_m = 0.05;
  g.offset_m = 0.03;
  g.casters = {CasterModule{0.25, 0.0}, CasterModule{0.25, 2.0 * kPi / 3.0},
               CasterModule{0.25, -2.0 * kPi / 3.0}};
  return g;
}

// Wheel rates from first principles: steering-axis velocity along the wheel (rolling) and zero
// lateral velocity of the trailing contact point.
CasterVector physicalRates(const CasterDriveGeometry& g, const std::array<double, 3>& steer,
                           const BodyTwist& w) {
  CasterVector out;
  for (std::size_t i = 0; i < 3; ++i) {
    const Vec2 axis =
        g.casters[i].d_m * Vec2(std::cos(g.casters[i].alpha_rad), std::sin(g.casters[i].alpha_rad));
    const Vec2 v_axis = Vec2(w(0), w(1)) + w(2) * Vec2(-axis.y(), axis.x());
    const Vec2 heading(std::cos(steer[i]), std::sin(steer[i]));
    const Vec2 lateral(-heading.y(), heading.x());
    const auto k = static_cast<Eigen::Index>(2 * i);
    out(k) = v_axis.dot(heading) / g.wheel_radius_m;
    // Contact = axis - eps * heading moves with v_axis + (Omega + phidot) x (-eps heading);
    // its lateral component is v_axis.lateral - eps (Omega + phidot) = 0.
    out(k + 1) = v_axis.dot(lateral) / g.offset_m - w(2);
  }
  return out;
}

TEST(CasterOdometry, JacobianMatchesTheRollingAndNoSlipConstraints) {
  const CasterDriveGeometry g = threeCasters();
  SimRandom rng(3);
  for (int i = 0; i < 100; ++i) {
    const std::array<double, 3> steer{6.0 * rng.uniform() - 3.0, 6.0 * rng.uniform() - 3.0,
                                      6.0 * rng.uniform() - 3.0};
    const BodyTwist w(rng.gaussian(), rng.gaussian(), rng.gaussian());
    const CasterVector expected = physicalRates(g, steer, w);
    const CasterVector got = casterJacobian(g, steer) * w;
    EXPECT_LT((got - expected).norm(), 1e-9 * (1.0 + expected.norm()));
  }
}

TEST(CasterOdometry, PseudoInverseReproducesAKnownTwistWithZeroResidual) {
  const CasterDriveGeometry g = threeCasters();
  const std::array<double, 3> steer{0.3, -0.4, 1.1};
  const BodyTwist twist(0.3, -0.05, 0.2);  // m/s, m/s, rad/s
  const double dt = 0.001;
  const CasterVector delta = physicalRates(g, steer, twist) * dt;
  const CasterOdometry odo = casterOdometry(g, steer, delta);
  ASSERT_TRUE(odo.ok);
  EXPECT_LT((odo.body_delta - twist * dt).norm(), 1e-12);
  EXPECT_LT(odo.residual_norm, 1e-12);
}

TEST(CasterOdometry, InconsistentWheelsLeaveAResidualAndTheLeastSquaresFit) {
  const CasterDriveGeometry g = threeCasters();
  const std::array<double, 3> steer{0.0, 0.0, 0.0};
  CasterVector delta = physicalRates(g, steer, BodyTwist(0.3, 0.0, 0.0)) * 0.01;
  delta(2) += 0.01;  // caster 2 slips forward by 0.01 rad
  const CasterOdometry odo = casterOdometry(g, steer, delta);
  ASSERT_TRUE(odo.ok);
  EXPECT_GT(odo.residual_norm, 1e-3);
  // The residual is orthogonal to the range of G (least-squares normal equations).
  EXPECT_LT((casterJacobian(g, steer).transpose() * odo.residual).norm(), 1e-9);
}

TEST(CasterOdometry, BadInputIsRejectedAndBadGeometryThrows) {
  CasterDriveGeometry g = threeCasters();
  CasterVector delta = CasterVector::Zero();
  delta(0) = std::nan("");
  EXPECT_FALSE(casterOdometry(g, {0, 0, 0}, delta).ok);
  EXPECT_FALSE(casterOdometry(g, {std::nan(""), 0, 0}, CasterVector::Zero()).ok);
  g.offset_m = 0.0;  // eps = 0 is not a caster (26)
  EXPECT_THROW(casterJacobian(g, {0, 0, 0}), std::invalid_argument);
}

}  // namespace
}  // namespace irgs
