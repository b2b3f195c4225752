#include "core/estimation/encoder_gyro_filter.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/estimation/dr_error_model.hpp"

namespace irgs {
namespace {

EncoderGyroFilterConfig quietConfig() {
  EncoderGyroFilterConfig c;
  c.wheelbase_m = 0.5;
  return c;
}

// The error model (3)/(8) in the project frame against the nonlinear step it linearises:
// propagate a computed and a true state one step and compare true - computed with F * delta.
TEST(DrErrorModel, TransitionMatchesTheNonlinearStepForSmallErrors) {
  DrStepGeometry g;
  g.right_m = 0.012;
  g.left_m = 0.007;
  g.psi_rad = 0.7;
  g.wheelbase_m = 0.5;
  g.omega_rad = 0.01;
  g.dt_s = 0.05;
  DrState delta;
  delta << 0.01, -0.02, 1e-3, 2e-3, -1e-3, 1.5e-3, -2e-3, 3e-3, 1e-4;

  // Computed (x, y, psi, phi) and true values.
  const double x = 1.0, y = 2.0, psi = g.psi_rad, phi = 0.69;
  const double rt = g.right_m * (1.0 + delta(kDrSr)), lt = g.left_m * (1.0 + delta(kDrSl));
  const double dt_true = g.wheelbase_m + delta(kDrDd);
  const double psit = psi + delta(kDrDpsi);
  DrState next;
  const double xc = x + std::cos(psi) * 0.5 * (g.right_m + g.left_m);
  const double yc = y + std::sin(psi) * 0.5 * (g.right_m + g.left_m);
  const double psic = psi + (g.right_m - g.left_m) / g.wheelbase_m;
  const double phic = phi + g.omega_rad;
  next(kDrDx) = (x + delta(kDrDx) + std::cos(psit) * 0.5 * (rt + lt)) - xc;
  next(kDrDy) = (y + delta(kDrDy) + std::sin(psit) * 0.5 * (rt + lt)) - yc;
  next(kDrDpsi) = (psit + (rt - lt) / dt_true) - psic;
  next(kDrDphi) =
      (phi + delta(kDrDphi) + (1.0 + delta(kDrDbs)) * g.omega_rad + delta(kDrDbrb) * g.dt_s) - phic;
  for (int i : {kDrSr, kDrSl, kDrDd, kDrDbs, kDrDbrb})
    next(i) = delta(i);

  const DrState linear = drTransition(g) * delta;
  for (int i = 0; i < kDrStates; ++i)
    EXPECT_NEAR(linear(i), next(i), 2e-7) << "state " << i;
}

// A001-4: with delta = true - computed, Z = psi_enc - phi_gyro = dphi - dpsi. Both headings
// equally uncertain, the gyro heading 0.1 rad ahead of the encoder heading: one update must meet
// in the middle (both at 0.05 rad). The wrong sign of H would push them apart instead (psi to
// -0.05, phi to 0.15): the feedback would double the difference.
TEST(EncoderGyroFilter, MeasurementSignPullsBothHeadingsTogether) {
  EncoderGyroFilterConfig c = quietConfig();
  c.initial_heading_stddev_rad = 0.2;
  c.gate_nis = std::numeric_limits<double>::infinity();
  EncoderGyroFilter filter(c, Pose2{0.0, 0.0, 0.0});
  // The gyro turns 0.1 rad (1 rad/s for 0.1 s) while the encoders report no rotation.
  const DrStepResult r = filter.step({0.0, 0.0, 1.0, 0.1});
  ASSERT_EQ(r.status, DrStepStatus::kUpdated);
  EXPECT_NEAR(r.innovation_rad, -0.1, 1e-12);  // psi - phi
  EXPECT_NEAR(filter.gyroHeading(), 0.05, 1e-3);
  EXPECT_NEAR(filter.pose().theta, 0.05, 1e-3);
  // Part of the excess rotation is explained as a gyro scale-factor error (scale below 1).
  EXPECT_LT(filter.sensorModel().gyro_scale, 1.0);
}

// The same with a trusted encoder heading: the gyro heading is pulled onto it.
TEST(EncoderGyroFilter, MeasurementSignPullsTheGyroHeadingOntoATrustedEncoderHeading) {
  EncoderGyroFilterConfig c = quietConfig();
  c.gate_nis = std::numeric_limits<double>::infinity();
  c.gyro_scale_stddev = 0.5;  // the gyro's scale is unknown, the encoders are exact
  c.encoder_scale_stddev = 1e-9;
  c.wheelbase_stddev_m = 1e-9;
  EncoderGyroFilter filter(c, Pose2{0.0, 0.0, 0.0});
  filter.step({0.0, 0.0, 1.0, 0.1});
  EXPECT_NEAR(filter.gyroHeading(), 0.0, 1e-3);
  EXPECT_NEAR(filter.pose().theta, 0.0, 1e-9);
}

TEST(EncoderGyroFilter, StationaryGyroBiasIsEstimatedAndKeptOutOfTheHeading) {
  EncoderGyroFilterConfig c = quietConfig();
  c.gyro_bias_stddev_radps = degToRad(0.05);
  EncoderGyroFilter filter(c, Pose2{});
  const double bias = degToRad(0.02);  // the gyro reads this at rest
  for (int k = 0; k < 2000; ++k)
    filter.step({0.0, 0.0, bias, 0.05});
  EXPECT_EQ(filter.mode(), DrFilterMode::kFiltering);
  EXPECT_NEAR(filter.sensorModel().gyro_bias_radps, bias, 0.02 * bias);
  EXPECT_NEAR(filter.pose().theta, 0.0, 1e-4);
  EXPECT_LT(std::sqrt(filter.covariance()(kDrDbrb, kDrDbrb)), 0.1 * c.gyro_bias_stddev_radps);
}

TEST(EncoderGyroFilter, DifferentialEncoderScaleIsLearnedDrivingStraightWithAPerfectGyro) {
  EncoderGyroFilterConfig c = quietConfig();
  c.gyro_scale_stddev = 1e-5;
  c.gyro_bias_stddev_radps = 1e-7;
  EncoderGyroFilter filter(c, Pose2{});
  // True motion straight at 0.2 m/s; the right encoder reads 0.4 % short (S_R = +0.004).
  const double dt = 0.05, ds = 0.2 * dt;
  for (int k = 0; k < 3000; ++k)
    filter.step({ds / 1.004, ds, 0.0, dt});
  const DrSensorModel& m = filter.sensorModel();
  // Only the differential is observable driving straight (digest 2.5).
  EXPECT_NEAR(m.right_scale - m.left_scale, 0.004, 2e-4);
  EXPECT_NEAR(filter.pose().theta, 0.0, 1e-3);
  EXPECT_GT(std::abs(filter.unfilteredPose().theta), 0.1);  // open-loop DR turned away
}

TEST(EncoderGyroFilter, NonFiniteInputIsRejectedAndChangesNothing) {
  EncoderGyroFilter filter(quietConfig(), Pose2{1.0, 2.0, 0.3});
  const DrCov before = filter.covariance();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(filter.step({nan, 0.0, 0.0, 0.1}).status, DrStepStatus::kRejectedNonFinite);
  EXPECT_EQ(filter.step({0.0, 0.0, nan, 0.1}).status, DrStepStatus::kRejectedNonFinite);
  EXPECT_EQ(filter.step({0.0, 0.0, 0.0, 0.0}).status, DrStepStatus::kRejectedNonFinite);
  EXPECT_EQ(filter.step({0.0, 0.0, 0.0, -1.0}).status, DrStepStatus::kRejectedNonFinite);
  EXPECT_EQ(filter.step({1e300, 0.0, 0.0, 0.1}).status, DrStepStatus::kRejectedNonFinite);
  EXPECT_EQ(filter.step({0.0, 0.0, 1e9, 0.1}).status, DrStepStatus::kRejectedNonFinite);
  EXPECT_EQ(filter.pose(), (Pose2{1.0, 2.0, 0.3}));
  EXPECT_EQ(filter.covariance(), before);
}

TEST(EncoderGyroFilter, MissingGyroPredictsOnlyAndGrowsNoFalseConfidence) {
  EncoderGyroFilter filter(quietConfig(), Pose2{});
  const DrStepResult r = filter.step({0.01, 0.01, std::nullopt, 0.05});
  EXPECT_EQ(r.status, DrStepStatus::kPredictedOnly);
  EXPECT_NEAR(filter.pose().x, 0.01, 1e-12);
  EXPECT_EQ(filter.updateCount(), 0);
}

TEST(EncoderGyroFilter, AGyroFaultIsGatedThenFallsBackToEncoderDeadReckoning) {
  EncoderGyroFilterConfig c = quietConfig();
  c.max_consecutive_gated = 10;
  EncoderGyroFilter filter(c, Pose2{});
  const double dt = 0.05, ds = 0.01;
  for (int k = 0; k < 100; ++k)
    ASSERT_EQ(filter.step({ds, ds, 0.0, dt}).status, DrStepStatus::kUpdated);
  // The gyro now reports a spin the wheels do not make.
  DrStepStatus last = DrStepStatus::kUpdated;
  int gated = 0;
  for (int k = 0; k < 20 && last != DrStepStatus::kFallback; ++k) {
    last = filter.step({ds, ds, 2.0, dt}).status;
    gated += last == DrStepStatus::kGated ? 1 : 0;
  }
  EXPECT_EQ(last, DrStepStatus::kFallback);
  EXPECT_GT(gated, 0);
  EXPECT_EQ(filter.mode(), DrFilterMode::kFallback);
  EXPECT_EQ(filter.fallbackReason(), DrFallbackReason::kInnovationTest);
  // From now on the pose is plain encoder DR: straight ahead, heading unaffected by the gyro.
  const Pose2 at_fallback = filter.pose();
  for (int k = 0; k < 10; ++k)
    EXPECT_EQ(filter.step({ds, ds, 2.0, dt}).status, DrStepStatus::kFallback);
  EXPECT_NEAR(filter.pose().x - at_fallback.x, 10 * ds, 1e-12);
  EXPECT_NEAR(filter.pose().theta, at_fallback.theta, 1e-12);
  EXPECT_LT(std::abs(filter.pose().theta), 0.05);
  // restart() re-arms it.
  filter.restart();
  EXPECT_EQ(filter.mode(), DrFilterMode::kFiltering);
  EXPECT_EQ(filter.step({ds, ds, 0.0, dt}).status, DrStepStatus::kUpdated);
}

TEST(EncoderGyroFilter, InvalidConfigurationThrows) {
  EncoderGyroFilterConfig c = quietConfig();
  c.wheelbase_m = 0.0;
  EXPECT_THROW(EncoderGyroFilter(c, Pose2{}), std::invalid_argument);
  c = quietConfig();
  c.measurement_variance_rad2 = 0.0;
  EXPECT_THROW(EncoderGyroFilter(c, Pose2{}), std::invalid_argument);
  c = quietConfig();
  c.encoder_scale_stddev = -1.0;
  EXPECT_THROW(EncoderGyroFilter(c, Pose2{}), std::invalid_argument);
  EXPECT_THROW(EncoderGyroFilter(quietConfig(), Pose2{std::nan(""), 0.0, 0.0}),
               std::invalid_argument);
}

}  // namespace
}  // namespace irgs
