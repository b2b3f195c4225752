// Paper 000's own robot in simulation: the three-caster steer/drive robot of
// resources/robots/caster3_000.json driven along the bundled Table-1 corridor at 0.3 m/s. The
// Simulator drives differential robots only, so the caster kinematics are simulated here: the
// truth moves with a constant body twist per 1 ms dead-reckoning period [000], each caster's
// true drive and steering rates follow (26) with its TRUE wheel radius, and the six encoder
// increments carry slip and steering backlash noise. The EKF predicts with the least-squares
// J+ odometry and the adaptive Q = lambda ||e|| (34)-(37) every 1 ms and updates with the three
// stereo sensors every 40 ms; dead reckoning is the same prediction without updates.
// Numbers: docs/localization.md.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <Eigen/Cholesky>

#include "core/estimation/caster_profile.hpp"
#include "core/estimation/ekf_localizer.hpp"
#include "core/estimation/mouse_sensor.hpp"
#include "core/estimation/stereo_echo_sim.hpp"
#include "core/estimation/stereo_measurement_model.hpp"
#include "core/robot/robot_profile_file.hpp"
#include "core/sim/random.hpp"
#include "core/world/map_file.hpp"

namespace irgs {
namespace {

constexpr double kDt = 0.001;        // dead-reckoning period [000: 1 ms]
constexpr int kStepsPerUpdate = 40;  // EKF period [000: 40 ms]
constexpr double kSpeed = 0.3;       // [000: about 0.3 m/s]

CasterDriveGeometry loadGeometry() {
  const RobotProfileResult loaded =
      loadRobotProfileFile(std::string(IRGS_SOURCE_DIR) + "/resources/robots/caster3_000.json");
  EXPECT_TRUE(loaded.ok());
  const CasterGeometryResult g = casterGeometryFromProfile(*loaded.profile);
  EXPECT_TRUE(g.geometry.has_value());
  return g.geometry.value_or(CasterDriveGeometry{});
}

struct CasterRun {
  double lambda = 0.005;                                   // [000]
  std::array<double, 3> radius_scale{1.01, 0.995, 1.004};  // true r / nominal r per caster [A]
  double drive_slip_stddev = 0.005;                        // relative, per increment [A]
  double steering_backlash_stddev_rad = 2e-4;              // per increment [A]
  std::uint64_t seed = 1;
};

struct CasterRunResult {
  double distance_m = 0.0;
  double max_ekf_error_m = 0.0, final_ekf_error_m = 0.0, final_ekf_heading_deg = 0.0;
  double final_dr_error_m = 0.0, max_dr_error_m = 0.0;
  double mean_residual_norm = 0.0;
  int periods = 0, nees_within_95 = 0, updates = 0, readings = 0;
  bool finished = false;
};

CasterRunResult run(const CasterRun& cfg) {
  const CasterDriveGeometry nominal = loadGeometry();
  const MapLoadResult loaded =
      loadMapFile(std::string(IRGS_SOURCE_DIR) + "/resources/maps/corridor_000_table1.json");
  EXPECT_TRUE(loaded.map.has_value());
  const WorldMap& map = *loaded.map;
  const LocalizationMap loc_map = buildLocalizationMap(map);
  StereoEchoNoise echo_noise;
  echo_noise.dropout_probability = 0.05;
  const StereoEchoSimulator sonar(map, {}, echo_noise);
  SimRandom motion_rng = SimRandom::stream(cfg.seed, 1);
  SimRandom sonar_rng = SimRandom::stream(cfg.seed, 2);
  const std::array<SensorMount, 3> mounts = {SensorMount{0.0, -0.2, -kPi / 2},
                                             SensorMount{0.0, 0.2, kPi / 2},
                                             SensorMount{0.25, 0.0, 0.0}};

  const Pose2 start{2.0, 0.775, 0.0};
  LocCov p0 = LocCov::Zero();
  p0.diagonal() << 0.01 * 0.01, 0.01 * 0.01, degToRad(1.0) * degToRad(1.0);
  EkfLocalizer ekf(toLocState(start), p0);
  EkfLocalizer dr(toLocState(start), p0);  // predictions only

  // One clockwise lap hugging the central block (about 70 m).
  const std::vector<Vec2> waypoints = {
      {15.9, 0.775}, {15.9, -14.55}, {-1.0, -14.55}, {-1.0, 0.775}, {2.0, 0.775}};
  Pose2 truth = start;
  std::array<double, 3> steering{0.0, 0.0, 0.0};  // trailing straight behind, moving forward
  CasterRunResult r;
  double residual_sum = 0.0;
  long steps = 0;
  std::size_t target = 0;
  for (; target < waypoints.size() && steps < 3'000'000; ++steps) {
    const Vec2 to_goal = waypoints[target] - truth.position();
    if (to_goal.norm() < 0.03) {
      ++target;
      continue;
    }
    const double heading_error = wrapAngle(std::atan2(to_goal.y(), to_goal.x()) - truth.theta);
    const double omega = std::clamp(2.0 * heading_error, -0.6, 0.6);
    const double v = std::abs(heading_error) > 0.1 ? 0.0 : std::min(kSpeed, to_goal.norm());
    const BodyTwist w(v, 0.0, omega);

    // True wheel rates from (26) with the true radii; steering moves with the no-slip row.
    const CasterG g_nominal = casterJacobian(nominal, steering);
    CasterVector delta = g_nominal * w * kDt;
    CasterVector measured;
    for (int i = 0; i < 3; ++i) {
      const auto k = static_cast<std::size_t>(i);
      delta(2 * i) /= cfg.radius_scale[k];  // a larger true wheel turns less for the same path
      steering[k] = wrapAngle(steering[k] + delta(2 * i + 1));
      measured(2 * i) = delta(2 * i) * (1.0 + cfg.drive_slip_stddev * motion_rng.gaussian());
      measured(2 * i + 1) =
          delta(2 * i + 1) + cfg.steering_backlash_stddev_rad * motion_rng.gaussian();
    }
    const std::array<double, 3> steering_before = {wrapAngle(steering[0] - delta(1)),
                                                   wrapAngle(steering[1] - delta(3)),
                                                   wrapAngle(steering[2] - delta(5))};
    const Pose2 next = applyIncrement(truth, {w(0) * kDt, w(1) * kDt, w(2) * kDt});
    r.distance_m += (next.position() - truth.position()).norm();
    truth = next;

    const CasterPrediction pred = ekf.predictCaster(nominal, steering_before, measured, cfg.lambda);
    EXPECT_EQ(pred.status, PredictStatus::kApplied);
    residual_sum += pred.residual_norm;
    dr.predictCaster(nominal, steering_before, measured, cfg.lambda);
    r.max_dr_error_m = std::max(r.max_dr_error_m, (dr.pose().position() - truth.position()).norm());

    if (steps % kStepsPerUpdate != 0)
      continue;
    for (const SensorMount& mount : mounts) {
      const SimulatedEcho echo = sonar.echo(sensorWorldPose(toLocState(truth), mount), sonar_rng);
      if (echo.status != EchoStatus::kEcho)
        continue;
      ++r.readings;
      if (ekf.update(echo.paths, {mount, 0.2}, loc_map).status == UpdateStatus::kUpdated)
        ++r.updates;
    }
    ++r.periods;
    r.max_ekf_error_m =
        std::max(r.max_ekf_error_m, (ekf.pose().position() - truth.position()).norm());
    LocState e = ekf.state() - toLocState(truth);
    e(kLocPhi) = wrapAngle(e(kLocPhi));
    if (e.dot(ekf.covariance().ldlt().solve(e)) <= 7.815)
      ++r.nees_within_95;
  }
  r.finished = target == waypoints.size();
  r.final_ekf_error_m = (ekf.pose().position() - truth.position()).norm();
  r.final_ekf_heading_deg = radToDeg(std::abs(wrapAngle(ekf.pose().theta - truth.theta)));
  r.final_dr_error_m = (dr.pose().position() - truth.position()).norm();
  r.mean_residual_norm = residual_sum / static_cast<double>(std::max(1L, steps));
  return r;
}

void print(const CasterRun& c, const CasterRunResult& r) {
  std::printf(
      "caster lambda %.3g seed %llu: %.1f m; EKF max %.3f m final %.3f m heading %.2f deg; DR "
      "final %.2f m (max %.2f m); %d/%d readings used; NEES within 95 %% bound %.1f %% of %d; "
      "mean ||e|| %.2e rad\n",
      c.lambda, static_cast<unsigned long long>(c.seed), r.distance_m, r.max_ekf_error_m,
      r.final_ekf_error_m, r.final_ekf_heading_deg, r.final_dr_error_m, r.max_dr_error_m, r.updates,
      r.readings, 100.0 * r.nees_within_95 / std::max(1, r.periods), r.periods,
      r.mean_residual_norm);
}

TEST(CasterCorridorRun, TheBundledProfileGivesThePapersThreeCasterGeometry) {
  const CasterDriveGeometry g = loadGeometry();
  EXPECT_GT(g.offset_m, 0.0);
  EXPECT_NEAR(g.casters[1].alpha_rad - g.casters[0].alpha_rad, degToRad(120.0), 1e-12);
  // G has full rank with the casters trailing straight: J+ exists.
  const CasterOdometry odo = casterOdometry(g, {0.0, 0.0, 0.0}, CasterVector::Zero());
  EXPECT_TRUE(odo.ok);
}

TEST(CasterCorridorRun, AProfileWithoutCasterGeometryIsADiagnostic) {
  RobotProfile profile;
  profile.drive.type = DriveType::kThreeCaster;
  EXPECT_FALSE(casterGeometryFromProfile(profile).geometry.has_value());
  profile.drive.extra["three_caster"] = {{"caster_offset_m", 0.0},
                                         {"casters", {{{"d_m", 0.2}, {"alpha_deg", 0}}}}};
  const CasterGeometryResult r = casterGeometryFromProfile(profile);
  EXPECT_FALSE(r.geometry.has_value());
  EXPECT_EQ(r.diagnostics.size(), 2u);  // eps = 0, and not three casters
}

TEST(CasterCorridorRun, EkfErrorStaysBoundedWhileCasterDeadReckoningGrows) {
  for (std::uint64_t seed : {1u, 2u}) {
    CasterRun c;
    c.seed = seed;
    const CasterRunResult r = run(c);
    print(c, r);
    ASSERT_TRUE(r.finished);
    EXPECT_GT(r.distance_m, 60.0);
    EXPECT_GT(r.mean_residual_norm, 0.0);  // the wheels disagree: the adaptive Q is active
    EXPECT_LT(r.max_ekf_error_m, 0.25) << "seed " << seed;
    EXPECT_LT(r.final_ekf_error_m, 0.1) << "seed " << seed;
    EXPECT_LT(r.final_ekf_heading_deg, 3.0) << "seed " << seed;
    EXPECT_GT(r.final_dr_error_m, 10.0 * r.final_ekf_error_m) << "seed " << seed;
    EXPECT_GT(r.updates, r.readings / 2) << "seed " << seed;
  }
}

// The paper's lambda = 0.005 was tuned for its robot; with our [A] wheel errors (1 % radius
// spread, 0.5 % slip) it is overconfident (about half the periods inside the NEES bound, while
// the error stays bounded). Ten times larger makes the filter consistent.
TEST(CasterCorridorRun, TheAdaptiveNoiseScaleDecidesConsistencyNotBoundedness) {
  for (double lambda : {0.005, 0.01, 0.02, 0.05, 0.5}) {
    CasterRun c;
    c.lambda = lambda;
    const CasterRunResult r = run(c);
    print(c, r);
    ASSERT_TRUE(r.finished);
    EXPECT_LT(r.max_ekf_error_m, 0.1);
    const double nees = static_cast<double>(r.nees_within_95) / r.periods;
    if (lambda == 0.005) {
      EXPECT_LT(nees, 0.9);  // overconfident with the paper's value
    }
    if (lambda >= 0.05) {
      EXPECT_GE(nees, 0.9);  // issue-5 acceptance band
    }
  }
}

}  // namespace
}  // namespace irgs
