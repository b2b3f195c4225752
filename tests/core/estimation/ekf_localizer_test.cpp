#include "core/estimation/ekf_localizer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "core/estimation/stereo_measurement_model.hpp"
#include "core/sim/random.hpp"

namespace irgs {
namespace {

constexpr double kFdStep = 1e-6;

LocRow finiteDifference(const std::function<double(const LocState&)>& h, const LocState& x,
                        bool angle) {
  LocRow j;
  for (int i = 0; i < kLocStateSize; ++i) {
    LocState xp = x, xm = x;
    xp(i) += kFdStep;
    xm(i) -= kFdStep;
    const double diff = h(xp) - h(xm);
    j(i) = (angle ? wrapAngle(diff) : diff) / (2.0 * kFdStep);
  }
  return j;
}

TEST(StereoMeasurementModel, SensorPoseUsesTheLeftPositiveMountingOffset) {
  // A000-1: a sensor mounted 0.2 m to the left of a robot heading +y sits at x = -0.2.
  const Pose2 t = sensorWorldPose({1.0, 1.0, kPi / 2}, {0.0, 0.2, kPi / 2});
  EXPECT_NEAR(t.x, 0.8, 1e-12);
  EXPECT_NEAR(t.y, 1.0, 1e-12);
  EXPECT_NEAR(std::abs(t.theta), kPi, 1e-12);
}

TEST(StereoMeasurementModel, JacobiansMatchFiniteDifferences) {
  SimRandom rng(5);
  for (int i = 0; i < 200; ++i) {
    const LocState x(4.0 * rng.uniform() - 2.0, 4.0 * rng.uniform() - 2.0,
                     wrapAngle(7.0 * rng.uniform()));
    const SensorMount mount{0.4 * rng.uniform() - 0.2, 0.4 * rng.uniform() - 0.2,
                            wrapAngle(7.0 * rng.uniform())};
    const FacingLine wall{wrapAngle(7.0 * rng.uniform()), 10.0 * rng.uniform() - 5.0};
    const Vec2 point(6.0 * rng.uniform() - 3.0 + 5.0, 6.0 * rng.uniform() - 3.0);

    const ScalarPrediction d = predictWallDistance(x, mount, wall);
    const LocRow fd_d = finiteDifference(
        [&](const LocState& s) { return predictWallDistance(s, mount, wall).value; }, x, false);
    EXPECT_LT((d.jacobian - fd_d).norm(), 1e-7);

    const ScalarPrediction b = predictWallBearing(x, mount, wall);
    const LocRow fd_b = finiteDifference(
        [&](const LocState& s) { return predictWallBearing(s, mount, wall).value; }, x, true);
    EXPECT_LT((b.jacobian - fd_b).norm(), 1e-7);

    const ScalarPrediction p = predictPointDistance(x, mount, point);
    const LocRow fd_p = finiteDifference(
        [&](const LocState& s) { return predictPointDistance(s, mount, point).value; }, x, false);
    EXPECT_LT((p.jacobian - fd_p).norm(), 1e-6);
  }
}

TEST(StereoMeasurementModel, WallPredictionsAgreeWithTheSharedWallModel) {
  const WallLine w = wallLineFromFace({{1, -1}, {1, 1}}, {+1, 0});  // P_V = -1 face
  const LocState x(2.5, 0.3, kPi - 0.1);
  const SensorMount mount{0.1, -0.05, 0.0};
  const Pose2 t = sensorWorldPose(x, mount);
  EXPECT_NEAR(predictWallDistance(x, mount, robotFacing(w)).value, predictedWallDistance(w, t),
              1e-12);
  EXPECT_NEAR(predictWallBearing(x, mount, robotFacing(w)).value, predictedWallBearing(w, t),
              1e-12);
}

LocCov covarianceAfterNoiselessPredict(const LocState& x0, const LocCov& p0, double l, double r) {
  EkfLocalizer ekf(x0, p0);
  DiffDriveNoise none;
  none.wheel_variance_per_m = 0.0;
  EXPECT_EQ(ekf.predictDiffDrive(l, r, 0.4, none), PredictStatus::kApplied);
  return ekf.covariance();
}

TEST(EkfLocalizer, DiffDrivePredictionJacobianMatchesFiniteDifferences) {
  const LocState x0(1.0, -2.0, 0.7);
  const double l = 0.05, r = 0.08, b = 0.4;
  auto f = [&](const LocState& x) {
    EkfLocalizer ekf(x, LocCov::Identity());
    DiffDriveNoise none;
    none.wheel_variance_per_m = 0.0;
    ekf.predictDiffDrive(l, r, b, none);
    return ekf.state();
  };
  LocCov fd;
  for (int i = 0; i < 3; ++i) {
    LocState xp = x0, xm = x0;
    xp(i) += kFdStep;
    xm(i) -= kFdStep;
    fd.col(i) = (f(xp) - f(xm)) / (2.0 * kFdStep);
  }
  const LocCov p0 = LocCov::Identity() * 0.01;
  EXPECT_LT((covarianceAfterNoiselessPredict(x0, p0, l, r) - fd * p0 * fd.transpose()).norm(),
            1e-9);
  // The mean follows the midpoint arc.
  const LocState x1 = f(x0);
  EXPECT_NEAR(x1(kLocPhi), 0.7 + 0.03 / b, 1e-12);
  EXPECT_NEAR(x1(kLocX), 1.0 + 0.065 * std::cos(0.7 + 0.015 / b), 1e-12);
}

TEST(EkfLocalizer, DiffDriveProcessNoiseGrowsWithTravel) {
  EkfLocalizer ekf(LocState::Zero(), LocCov::Zero());
  DiffDriveNoise noise;
  noise.wheel_variance_per_m = 1e-4;
  for (int i = 0; i < 100; ++i)
    ekf.predictDiffDrive(0.01, 0.01, 0.4, noise);
  // Each wheel: variance 1e-4 per metre over 1 m; heading variance 2e-4 / B^2.
  EXPECT_NEAR(ekf.covariance()(kLocPhi, kLocPhi), 2e-4 / 0.16, 1e-9);
  EXPECT_GT(ekf.covariance()(kLocY, kLocY), 0.0);
  EXPECT_NEAR(ekf.covariance()(kLocX, kLocX), 0.5e-4, 1e-9);
}

TEST(EkfLocalizer, NonFiniteInputsAreRejectedAndLeaveTheFilterUnchanged) {
  EkfLocalizer ekf(LocState(1.0, 2.0, 0.3), LocCov::Identity() * 0.01);
  const LocState x = ekf.state();
  const LocCov p = ekf.covariance();
  EXPECT_EQ(ekf.predictDiffDrive(std::nan(""), 0.1, 0.4, {}), PredictStatus::kRejectedNonFinite);
  EXPECT_EQ(ekf.predictDiffDrive(0.1, 0.1, 0.0, {}), PredictStatus::kRejectedNonFinite);
  EXPECT_EQ(ekf.predictBodyIncrement(BodyTwist(INFINITY, 0, 0), LocCov::Zero()),
            PredictStatus::kRejectedNonFinite);
  LocalizationMap map;
  map.walls.push_back({"w", WallLine{3.0, 0.0, 1}, robotFacing(WallLine{3.0, 0.0, 1}), {}});
  EXPECT_EQ(ekf.update({std::nan(""), 4.0}, {}, map).status, UpdateStatus::kRejectedNonFinite);
  EXPECT_EQ(ekf.updateWithDistanceBearing(1.0, std::nan(""), {}, map).status,
            UpdateStatus::kRejectedNonFinite);
  EXPECT_EQ(ekf.update({0.1, 0.1}, {}, map).status, UpdateStatus::kInvalidEcho);
  EXPECT_EQ(ekf.state(), x);
  EXPECT_EQ(ekf.covariance(), p);
  LocCov bad = LocCov::Identity();
  bad(0, 1) = 0.5;  // not symmetric
  EXPECT_THROW(EkfLocalizer(LocState::Zero(), bad), std::invalid_argument);
  EXPECT_THROW(EkfLocalizer(LocState::Zero(), -LocCov::Identity()), std::invalid_argument);
  EkfLocalizerConfig cfg;
  cfg.r_d_m2 = 0.0;
  EXPECT_THROW(EkfLocalizer(LocState::Zero(), LocCov::Identity(), cfg), std::invalid_argument);
}

// One wall x = 3 facing the origin, a corner at (3, 2) and an edge at (3, -2).
LocalizationMap smallMap() {
  WorldMap world;
  world.walls.push_back({"W", {{3.0, -2.0}, {3.0, 2.0}}, false, {}});
  world.features.push_back({"C", PointFeatureKind::kCorner, {3.0, 2.0}, {}});
  world.features.push_back({"E", PointFeatureKind::kEdge, {3.0, -2.0}, {}});
  return buildLocalizationMap(world);
}

TEST(EkfLocalizer, WallReadingMatchesTheFacingFaceAndCorrectsDistanceAndHeading) {
  const LocalizationMap map = smallMap();
  ASSERT_EQ(map.walls.size(), 2u);  // both faces
  const LocState truth(0.0, 0.0, 0.05);
  EkfLocalizer ekf(LocState(0.1, 0.0, 0.0), LocCov::Identity() * 0.04);
  const StereoSensor sensor{{0.2, 0.0, 0.0}, 0.2};
  const Pose2 t = sensorWorldPose(truth, sensor.mount);
  const EchoPaths reading =
      wallEchoPaths(wallLineFacing(map.walls[0].segment, t.position()), t, sensor.half_baseline_m);
  const LocalizationUpdate u = ekf.update(reading, sensor, map);
  ASSERT_EQ(u.status, UpdateStatus::kUpdated);
  EXPECT_EQ(u.match, MatchKind::kWall);
  EXPECT_EQ(u.feature_id, "W");
  EXPECT_GT(map.walls[u.feature_index].facing.p_eff_m, 0.0);  // the face towards the origin
  EXPECT_TRUE(u.distance.applied);
  EXPECT_TRUE(u.bearing.applied);
  EXPECT_NEAR(u.distance.innovation, 0.1, 1e-3);
  EXPECT_LT(std::abs(ekf.state()(kLocX)), 0.01);
  EXPECT_LT(std::abs(ekf.state()(kLocPhi) - 0.05), 0.005);
  EXPECT_LT(ekf.covariance()(kLocX, kLocX), 0.001);
  EXPECT_NEAR(ekf.covariance()(kLocY, kLocY), 0.04, 1e-3);  // across the normal: unobserved
  EXPECT_TRUE(ekf.covariance().isApprox(ekf.covariance().transpose(), 0.0));
}

TEST(EkfLocalizer, CornersAndEdgesMatchFirstAndUpdateDistanceOnly) {
  const LocalizationMap map = smallMap();
  const StereoSensor sensor{{0.0, 0.0, 0.0}, 0.2};
  {
    EkfLocalizer ekf(LocState(1.0, 1.0, kPi / 4), LocCov::Identity() * 0.01);
    const Pose2 t = sensorWorldPose(LocState(1.0, 1.02, kPi / 4), sensor.mount);
    const LocalizationUpdate u = ekf.update(cornerEchoPaths({3.0, 2.0}, t, 0.2), sensor, map);
    ASSERT_EQ(u.status, UpdateStatus::kUpdated);
    EXPECT_EQ(u.match, MatchKind::kCorner);
    EXPECT_EQ(u.feature_id, "C");
    EXPECT_FALSE(u.bearing.attempted);
  }
  {
    EkfLocalizer ekf(LocState(1.5, -1.5, -0.3), LocCov::Identity() * 0.01);
    const Pose2 t = sensorWorldPose(LocState(1.5, -1.5, -0.3), sensor.mount);
    const LocalizationUpdate u = ekf.update(edgeEchoPaths({3.0, -2.0}, t, 0.2), sensor, map);
    ASSERT_EQ(u.status, UpdateStatus::kUpdated);
    EXPECT_EQ(u.match, MatchKind::kEdge);
    // The edge inverse gives the exact distance: zero innovation at the true pose.
    EXPECT_NEAR(u.distance.innovation, 0.0, 1e-9);
    EXPECT_NEAR(u.measured_d_m, std::hypot(1.5, 0.5), 1e-9);
  }
}

TEST(EkfLocalizer, ReadingsThatMatchNothingAreReportedAndGateRejectsOutliers) {
  const LocalizationMap map = smallMap();
  EkfLocalizer ekf(LocState(0.0, 0.0, 0.0), LocCov::Identity() * 0.01);
  // Bearing 40 deg off any wall normal and far from every point.
  EXPECT_EQ(ekf.updateWithDistanceBearing(1.0, degToRad(40.0), {}, map).status,
            UpdateStatus::kNoMatch);
  EkfLocalizerConfig cfg;
  cfg.gate = 9.0;  // 3 sigma
  EkfLocalizer gated(LocState(0.0, 0.0, 0.0), LocCov::Identity() * 0.0001, cfg);
  const LocalizationUpdate u = gated.updateWithDistanceBearing(2.0, 0.15, {}, map);  // d^ = 3
  EXPECT_EQ(u.status, UpdateStatus::kGated);
  EXPECT_EQ(u.match, MatchKind::kWall);
  EXPECT_GT(u.distance.nis, 9.0);
  EXPECT_GT(u.bearing.nis, 9.0);
  EXPECT_FALSE(u.distance.applied);
  EXPECT_EQ(gated.state(), LocState(0.0, 0.0, 0.0));
}

TEST(EkfLocalizer, BearingInnovationIsWrappedAcrossPlusMinusPi) {
  // Wall x = -1 whose face looks towards +x (phi_eff = pi). The robot truly heads -pi + 0.01;
  // the estimate says pi - 0.01. Without wrapping the innovation would be about 2 pi.
  LocalizationMap map;
  const Segment seg{{-1, -2}, {-1, 2}};
  const WallLine w = wallLineFromFace(seg, {+1, 0});
  map.walls.push_back({"w", w, robotFacing(w), seg});
  EkfLocalizer ekf(LocState(0.0, 0.0, kPi - 0.01), LocCov::Identity() * 0.01);
  const double true_heading = -kPi + 0.01;
  const double measured = wrapAngle(robotFacing(w).phi_eff_rad - true_heading);  // -0.01
  const LocalizationUpdate u = ekf.updateWithDistanceBearing(1.0, measured, {}, map);
  ASSERT_EQ(u.status, UpdateStatus::kUpdated);
  EXPECT_NEAR(u.bearing.innovation, -0.02, 1e-9);
  const double phi = ekf.state()(kLocPhi);
  EXPECT_GT(phi, -kPi);
  EXPECT_LE(phi, kPi);
  EXPECT_LT(std::abs(wrapAngle(phi - true_heading)), 0.01);
}

TEST(EkfLocalizer, CasterPredictionMovesByTheRotatedLeastSquaresTwistWithAdaptiveNoise) {
  CasterDriveGeometry g;
  g.wheel_radius_m = 0.05;
  g.offset_m = 0.03;
  g.casters = {CasterModule{0.25, 0.0}, CasterModule{0.25, 2.0 * kPi / 3.0},
               CasterModule{0.25, -2.0 * kPi / 3.0}};
  const std::array<double, 3> steer{0.2, 0.5, -0.3};
  const BodyTwist twist(0.3, 0.1, 0.2);
  const double dt = 0.001;
  const CasterVector consistent = casterJacobian(g, steer) * twist * dt;

  EkfLocalizer ekf(LocState(1.0, 2.0, kPi / 2), LocCov::Zero());
  const CasterPrediction p = ekf.predictCaster(g, steer, consistent, 0.005);
  ASSERT_EQ(p.status, PredictStatus::kApplied);
  EXPECT_LT(p.residual_norm, 1e-12);
  // (34) with R(Phi) body -> world (A000-2), midpoint heading: forward (+x body) is +y world.
  const double a = kPi / 2 + 0.5 * twist(2) * dt;
  EXPECT_NEAR(ekf.state()(kLocX), 1.0 + dt * (std::cos(a) * 0.3 - std::sin(a) * 0.1), 1e-12);
  EXPECT_NEAR(ekf.state()(kLocY), 2.0 + dt * (std::sin(a) * 0.3 + std::cos(a) * 0.1), 1e-12);
  EXPECT_NEAR(ekf.covariance().norm(), 0.0, 1e-15);  // consistent wheels: Q = 0 (36)

  CasterVector slipping = consistent;
  slipping(4) += 0.002;  // caster 3 drive slips
  const CasterPrediction q = ekf.predictCaster(g, steer, slipping, 0.005);
  ASSERT_EQ(q.status, PredictStatus::kApplied);
  EXPECT_GT(q.residual_norm, 1e-4);
  EXPECT_GT(ekf.covariance().trace(), 0.0);  // (36)/(37): Q = lambda ||e|| I6 through J+
  EXPECT_EQ(ekf.predictCaster(g, steer, slipping, -1.0).status, PredictStatus::kRejectedNonFinite);
}

}  // namespace
}  // namespace irgs
