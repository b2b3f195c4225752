#include "core/calibration/umbmark.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

namespace irgs {
namespace {

const UmbmarkSetup kSetup{4.0, 0.3571};

std::vector<UmbmarkRun> syntheticRuns(double e_d, double e_b, int n, double jitter_m = 0.0) {
  std::vector<UmbmarkRun> runs;
  const Vec2 cw = predictUmbmarkError(UmbmarkDirection::kClockwise, kSetup, e_d, e_b);
  const Vec2 ccw = predictUmbmarkError(UmbmarkDirection::kCounterClockwise, kSetup, e_d, e_b);
  for (int i = 0; i < n; ++i) {
    // Symmetric jitter: cancels in the centre of gravity, shows in the spread.
    const double j = (i % 2 == 0 ? 1.0 : -1.0) * jitter_m;
    runs.push_back({UmbmarkDirection::kClockwise, cw + Vec2(j, -j)});
    runs.push_back({UmbmarkDirection::kCounterClockwise, ccw + Vec2(-j, j)});
  }
  return runs;
}

TEST(Umbmark, APerfectRobotReturnsToItsStartAndNeedsNoCorrection) {
  EXPECT_LT(predictUmbmarkError(UmbmarkDirection::kClockwise, kSetup, 1.0, 1.0).norm(), 1e-12);
  const UmbmarkAnalysis a = analyseUmbmark(syntheticRuns(1.0, 1.0, 5), kSetup);
  ASSERT_TRUE(a.ok);
  EXPECT_NEAR(a.wheel_diameter_ratio, 1.0, 1e-9);
  EXPECT_NEAR(a.wheelbase_ratio, 1.0, 1e-9);
  EXPECT_TRUE(std::isinf(a.radius_m));
  EXPECT_LT(a.e_max_syst_m, 1e-12);
}

// The signs in our frames (x forward, y left, CCW positive), docs/calibration.md (U3)-(U4): a
// wheelbase larger than believed (E_b > 1) under-turns, so both squares end behind the start
// (x < 0), the clockwise one to the right of it (y < 0), the counter-clockwise one to the left; a
// larger right wheel (E_d > 1) curves every leg to the left.
TEST(Umbmark, ForwardModelSignsFollowTheDerivation) {
  const Vec2 cw_b = predictUmbmarkError(UmbmarkDirection::kClockwise, kSetup, 1.0, 1.02);
  const Vec2 ccw_b = predictUmbmarkError(UmbmarkDirection::kCounterClockwise, kSetup, 1.0, 1.02);
  const double alpha = 0.5 * kPi * (1.0 - 1.0 / 1.02);
  // First order (docs/calibration.md): x_cw = -2L(beta + alpha), x_ccw = 2L(beta - alpha),
  // y_cw = -2L(beta + alpha), y_ccw = -2L(beta - alpha).
  EXPECT_NEAR(cw_b.x(), -2.0 * 4.0 * alpha, 0.05 * 8.0 * alpha);
  EXPECT_NEAR(ccw_b.x(), -2.0 * 4.0 * alpha, 0.05 * 8.0 * alpha);
  EXPECT_NEAR(cw_b.y(), -2.0 * 4.0 * alpha, 0.1 * 8.0 * alpha);
  EXPECT_NEAR(ccw_b.y(), 2.0 * 4.0 * alpha, 0.1 * 8.0 * alpha);
  const Vec2 cw_d = predictUmbmarkError(UmbmarkDirection::kClockwise, kSetup, 1.005, 1.0);
  const Vec2 ccw_d = predictUmbmarkError(UmbmarkDirection::kCounterClockwise, kSetup, 1.005, 1.0);
  const double beta = 4.0 * (2.0 * 0.005 / 2.005) / kSetup.wheelbase_m;
  EXPECT_NEAR(cw_d.x(), -2.0 * 4.0 * beta, 0.1 * 8.0 * beta);
  EXPECT_NEAR(ccw_d.x(), 2.0 * 4.0 * beta, 0.1 * 8.0 * beta);
  EXPECT_NEAR(cw_d.y(), -2.0 * 4.0 * beta, 0.2 * 8.0 * beta);
  EXPECT_NEAR(ccw_d.y(), -2.0 * 4.0 * beta, 0.2 * 8.0 * beta);
}

TEST(Umbmark, KnownRatiosAreRecoveredExactlyByTheModelFitAndCloselyByThePapersFormulas) {
  for (const auto& [e_d, e_b] : std::vector<std::pair<double, double>>{
           {1.01, 1.03}, {0.995, 0.98}, {1.002, 1.0}, {1.0, 1.05}, {0.99, 1.01}}) {
    const UmbmarkAnalysis a = analyseUmbmark(syntheticRuns(e_d, e_b, 6, 0.01), kSetup);
    ASSERT_TRUE(a.ok) << e_d << " " << e_b;
    EXPECT_EQ(a.cw_runs, 6u);
    EXPECT_EQ(a.ccw_runs, 6u);
    EXPECT_NEAR(a.spread_cw_m, 0.01 * std::sqrt(2.0), 1e-12);
    EXPECT_NEAR(a.wheel_diameter_ratio, e_d, 1e-9) << e_d << " " << e_b;
    EXPECT_NEAR(a.wheelbase_ratio, e_b, 1e-9) << e_d << " " << e_b;
    EXPECT_LT(a.fit_residual_m, 1e-9);
    // The closed form is first order: E_d of the right sign, close only for small errors (with
    // both errors at once its cross terms are large, which is why the corrections use the fit).
    EXPECT_GE((a.wheel_diameter_ratio_linear - 1.0) * (e_d - 1.0), 0.0);
    if (std::abs(e_d - 1.0) + std::abs(e_b - 1.0) <= 0.002) {
      EXPECT_NEAR(a.wheel_diameter_ratio_linear, e_d, 0.1 * std::abs(e_d - 1.0) + 1e-6);
    }
  }
}

TEST(Umbmark, ErrorMeasureIsTheLargerCentreOfGravityDistance) {
  const std::vector<UmbmarkRun> runs = {{UmbmarkDirection::kClockwise, {0.3, 0.4}},
                                        {UmbmarkDirection::kClockwise, {0.3, 0.4}},
                                        {UmbmarkDirection::kCounterClockwise, {0.1, 0.0}}};
  const UmbmarkAnalysis a = analyseUmbmark(runs, kSetup);
  EXPECT_NEAR(a.e_max_syst_m, 0.5, 1e-12);
  EXPECT_NEAR(a.alpha_rad, (0.3 + 0.1) / -16.0, 1e-12);  // (U3)
  EXPECT_NEAR(a.beta_rad, (0.3 - 0.1) / -16.0, 1e-12);   // (U4)
}

TEST(Umbmark, MissingDirectionsAndNonFiniteRunsAreReportedNotThrown) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<UmbmarkRun> runs = {{UmbmarkDirection::kClockwise, {0.1, 0.1}},
                                        {UmbmarkDirection::kCounterClockwise, {nan, 0.0}}};
  const UmbmarkAnalysis a = analyseUmbmark(runs, kSetup);
  EXPECT_FALSE(a.ok);
  ASSERT_EQ(a.diagnostics.size(), 2u);
  EXPECT_NE(a.diagnostics[0].find("run 2"), std::string::npos);
  EXPECT_FALSE(analyseUmbmark({}, kSetup).ok);
  // Centimetres typed as metres: far beyond the model.
  const std::vector<UmbmarkRun> huge = {{UmbmarkDirection::kClockwise, {30.0, 4.0}},
                                        {UmbmarkDirection::kCounterClockwise, {-10.0, 2.0}}};
  const UmbmarkAnalysis h = analyseUmbmark(huge, kSetup);
  EXPECT_FALSE(h.ok);
  EXPECT_FALSE(h.diagnostics.empty());
  EXPECT_THROW(analyseUmbmark(runs, UmbmarkSetup{0.0, 0.3}), std::invalid_argument);
  EXPECT_THROW(analyseUmbmark(runs, UmbmarkSetup{4.0, nan}), std::invalid_argument);
}

TEST(Umbmark, CorrectionsFollowThePapersEquation17AndCompose) {
  const OdometryCorrection c = correctOdometry({1.0, 1.0, 0.4}, 1.01, 1.03);
  EXPECT_NEAR(c.left_wheel_scale, 2.0 / 2.01, 1e-12);
  EXPECT_NEAR(c.right_wheel_scale, 2.0 / (1.0 / 1.01 + 1.0), 1e-12);
  EXPECT_NEAR(c.right_wheel_scale / c.left_wheel_scale, 1.01, 1e-12);
  EXPECT_NEAR(c.wheelbase_m, 0.412, 1e-12);
  // A second round on the corrected odometry multiplies, keeping the mean wheel at 1.
  const OdometryCorrection c2 = correctOdometry(c, 1.001, 1.0);
  EXPECT_NEAR(0.5 * (c2.left_wheel_scale + c2.right_wheel_scale), 1.0, 1e-12);
  EXPECT_NEAR(c2.right_wheel_scale / c2.left_wheel_scale, 1.01 * 1.001, 1e-12);
  EXPECT_THROW(correctOdometry({0.0, 1.0, 0.4}, 1.0, 1.0), std::invalid_argument);
  EXPECT_THROW(correctOdometry({1.0, 1.0, 0.4}, -1.0, 1.0), std::invalid_argument);
}

}  // namespace
}  // namespace irgs
