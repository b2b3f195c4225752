// Optical-mouse sensor model and two-sensor pose inference of paper 004 (digest 5.2-5.4).

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "core/estimation/mouse_odometry.hpp"
#include "core/robot/robot_profile_file.hpp"
#include "core/sim/random.hpp"

namespace irgs {
namespace {

constexpr double kExact = 1e-12;

void expectMotionRecovered(const MouseRig& rig, const BodyIncrement& inc) {
  const TwoSensorMotion m = inferTwoSensorMotion(rig, sensorDisplacement(rig.right, inc),
                                                 sensorDisplacement(rig.left, inc));
  const Pose2 truth = applyIncrement({}, inc);
  EXPECT_EQ(m.status, MouseMotionStatus::kOk);
  EXPECT_NEAR(m.dtheta_rad, inc.dtheta_rad, kExact);
  EXPECT_NEAR(m.centre.x(), truth.x, kExact);
  EXPECT_NEAR(m.centre.y(), truth.y, kExact);
  EXPECT_NEAR(m.rigidity_residual_m, 0.0, kExact);
}

TEST(MouseSensor, PaperValuesConvertToSiUnits) {
  const MouseSensorSpec spec;
  EXPECT_DOUBLE_EQ(spec.metresPerCount(), 0.0254 / 800.0);  // 0.03175 mm at 800 cpi
  EXPECT_NEAR(spec.max_speed_mps, 0.5334, 1e-12);           // 21 in/s
  EXPECT_DOUBLE_EQ(spec.max_lift_m, 0.002);
}

TEST(MouseSensor, SingleSensorMotionUsesAtan2AndHypotInEveryQuadrant) {
  EXPECT_NEAR(sensorMotion(0.0, 0.01).alpha_rad, kPi / 2, kExact);  // (3) divides by 0 here
  EXPECT_NEAR(sensorMotion(-0.01, 0.0).alpha_rad, kPi, kExact);     // alpha = pi: l = |x-bar|
  EXPECT_NEAR(sensorMotion(-0.01, 0.0).length_m, 0.01, kExact);
  const SensorMotion m = sensorMotion(-0.03, -0.04);
  EXPECT_NEAR(m.length_m, 0.05, kExact);
  // (1)/(2) reproduce the readings.
  EXPECT_NEAR(m.length_m * std::cos(m.alpha_rad), -0.03, kExact);
  EXPECT_NEAR(m.length_m * std::sin(m.alpha_rad), -0.04, kExact);
  EXPECT_EQ(sensorMotion(0.0, 0.0).length_m, 0.0);
}

TEST(MouseSensor, IncrementBetweenInvertsApplyIncrement) {
  SimRandom rng(7);
  for (int i = 0; i < 200; ++i) {
    const Pose2 start{rng.gaussian(), rng.gaussian(), 3.0 * rng.gaussian()};
    const BodyIncrement inc{0.2 * rng.gaussian(), 0.05 * rng.gaussian(), rng.gaussian()};
    if (std::abs(inc.dtheta_rad) >= 3.0)
      continue;
    const BodyIncrement back = incrementBetween(start, applyIncrement(start, inc));
    EXPECT_NEAR(back.dx_m, inc.dx_m, 1e-12);
    EXPECT_NEAR(back.dy_m, inc.dy_m, 1e-12);
    EXPECT_NEAR(back.dtheta_rad, inc.dtheta_rad, 1e-12);
  }
}

TEST(MouseOdometry, PoseInferenceReproducesAStraightMotionExactly) {
  const MouseRig rig = symmetricMouseRig(0.2);
  expectMotionRecovered(rig, {0.05, 0.0, 0.0});
  expectMotionRecovered(rig, {-0.03, 0.0, 0.0});   // backwards
  expectMotionRecovered(rig, {0.02, 0.015, 0.0});  // diagonal (a slipping robot)
}

TEST(MouseOdometry, PoseInferenceReproducesArcsExactly) {
  const MouseRig rig = symmetricMouseRig(0.2);
  expectMotionRecovered(rig, {0.05, 0.0, 0.3});     // left arc
  expectMotionRecovered(rig, {0.05, 0.0, -0.3});    // right arc
  expectMotionRecovered(rig, {0.3, 0.0, 1.2});      // a long interval, r = 0.25 m
  expectMotionRecovered(rig, {0.05, 0.0, 1e-9});    // the straight limit (A004-6)
  expectMotionRecovered(rig, {0.05, 0.0, -0.5});    // turning about the right sensor: l_r = 0
  expectMotionRecovered(rig, {0.04, -0.01, -0.7});  // arc with lateral slip
}

TEST(MouseOdometry, PoseInferenceReproducesSpinsInPlaceExactly) {
  const MouseRig rig = symmetricMouseRig(0.2);
  expectMotionRecovered(rig, {0.0, 0.0, 0.5});
  expectMotionRecovered(rig, {0.0, 0.0, -2.5});
}

TEST(MouseOdometry, PoseInferenceIsExactForRotatedAndOffCentreSensors) {
  MouseRig rig;
  rig.right = {0.10, -0.07, degToRad(-30.0)};
  rig.left = {-0.05, 0.12, degToRad(100.0)};
  expectMotionRecovered(rig, {0.05, 0.0, 0.0});
  expectMotionRecovered(rig, {0.05, 0.01, 0.4});
  expectMotionRecovered(rig, {0.0, 0.0, -1.0});
}

// The printed equations (1)-(12) in paper 004's own frame (x lateral right, y forward, right
// sensor at +D/2), with gamma = alpha_r - alpha_l (A004-2); must agree with our body-frame
// implementation under x_body = y_004, y_body = -x_004 (A004-1).
TEST(MouseOdometry, AgreesWithThePrintedEquationsInThePapersFrame) {
  const double d = 0.2;
  const MouseRig rig = symmetricMouseRig(d);
  for (const BodyIncrement inc : {BodyIncrement{0.05, 0.0, 0.3}, BodyIncrement{0.08, 0.01, -0.6},
                                  BodyIncrement{0.0, 0.0, 0.9}}) {
    const Vec2 cr = sensorDisplacement(rig.right, inc), cl = sensorDisplacement(rig.left, inc);
    // Readings in the paper's frame.
    const double xr = -cr.y(), yr = cr.x(), xl = -cl.y(), yl = cl.x();
    const double ar = std::atan2(yr, xr), lr = std::hypot(xr, yr);
    const double al = std::atan2(yl, xl), ll = std::hypot(xl, yl);
    const double gamma = ar - al;
    const double dth = std::sqrt(ll * ll + lr * lr - 2.0 * std::cos(gamma) * ll * lr) / d *
                       (yr - yl > 0 ? 1.0 : -1.0);                  // (6)
    const double rr = lr / std::abs(dth), rl = ll / std::abs(dth);  // (4), (5)
    const double sg = dth > 0 ? 1.0 : -1.0;
    const double xr1 = rr * (std::sin(ar + dth) - std::sin(ar)) * sg + d / 2;  // (7)
    const double yr1 = rr * (std::cos(ar) - std::cos(ar + dth)) * sg;          // (8)
    const double xl1 = rl * (std::sin(al + dth) - std::sin(al)) * sg - d / 2;  // (9)
    const double yl1 = rl * (std::cos(al) - std::cos(al + dth)) * sg;          // (10)
    const double dx = 0.5 * (xr1 + xl1), dy = 0.5 * (yr1 + yl1);               // (11), (12)

    const TwoSensorMotion m = inferTwoSensorMotion(rig, cr, cl);
    EXPECT_NEAR(m.dtheta_rad, dth, 1e-12);
    EXPECT_NEAR(m.centre.x(), dy, 1e-12);
    EXPECT_NEAR(m.centre.y(), -dx, 1e-12);
  }
}

TEST(MouseOdometry, IntegratesAQuantisedCircleToWithinAMillimetre) {
  const MouseRig rig = symmetricMouseRig(0.2);
  MouseSensorSimulator right(rig.spec, rig.right), left(rig.spec, rig.left);
  SimRandom rng(3);
  MouseOdometry odo(rig, {1.0, 2.0, 0.5});
  Pose2 truth{1.0, 2.0, 0.5};
  const double dt = 0.01, v = 0.3, radius = 0.5;
  const int steps = static_cast<int>(std::round(2.0 * kPi * radius / v / dt));
  for (int i = 0; i < steps; ++i) {
    const BodyIncrement inc{v * dt, 0.0, v / radius * dt};
    truth = applyIncrement(truth, inc);
    const TwoSensorMotion m =
        odo.update(right.sample(inc, dt, 0.001, rng), left.sample(inc, dt, 0.001, rng));
    ASSERT_EQ(m.status, MouseMotionStatus::kOk);
  }
  // Counts quantised at 800 cpi (0.03 mm), sub-count motion carried: about 3.1 m of path.
  EXPECT_LT((odo.pose().position() - truth.position()).norm(), 1e-3);
  EXPECT_LT(std::abs(wrapAngle(odo.pose().theta - truth.theta)), 1e-3);
  EXPECT_NEAR(odo.distance_m(), 2.0 * kPi * radius, 0.01);
}

TEST(MouseSensor, QuantisationCarriesSubCountMotion) {
  const MouseSensorSpec spec;
  MouseSensorSimulator sensor(spec, {});
  SimRandom rng(1);
  std::int64_t total = 0;
  for (int i = 0; i < 1000; ++i)  // 0.01 count per interval
    total += sensor.sample({0.01 * spec.metresPerCount(), 0.0, 0.0}, 0.001, 0.0, rng).dx;
  EXPECT_EQ(total, 10);
}

TEST(MouseSensor, CountsSaturateAboveTheMaximumSpeed) {
  const MouseRig rig = symmetricMouseRig(0.2);
  MouseSensorSimulator right(rig.spec, rig.right), left(rig.spec, rig.left);
  SimRandom rng(1);
  MouseOdometry odo(rig, {});
  const double dt = 0.01;
  for (int i = 0; i < 100; ++i) {  // 1 s at 0.8 m/s, beyond 21 in/s
    const BodyIncrement inc{0.8 * dt, 0.0, 0.0};
    const MouseCounts r = right.sample(inc, dt, 0.0, rng);
    EXPECT_EQ(r.status, MouseStatus::kSaturated);
    EXPECT_EQ(odo.update(r, left.sample(inc, dt, 0.0, rng)).status, MouseMotionStatus::kSaturated);
  }
  EXPECT_NEAR(odo.pose().x, 0.5334, 1e-4);  // under-reported: the clipped speed
  EXPECT_EQ(odo.saturatedIntervals(), 100);
}

TEST(MouseSensor, ReportsNothingWhenLiftedMoreThanTwoMillimetres) {
  const MouseRig rig = symmetricMouseRig(0.2);
  MouseSensorSimulator right(rig.spec, rig.right), left(rig.spec, rig.left);
  SimRandom rng(1);
  MouseOdometry odo(rig, {});
  const BodyIncrement inc{0.003, 0.0, 0.0};
  const MouseCounts lifted = right.sample(inc, 0.01, 0.0021, rng);
  EXPECT_EQ(lifted.status, MouseStatus::kLifted);
  EXPECT_EQ(lifted.dx, 0);
  EXPECT_EQ(odo.update(lifted, left.sample(inc, 0.01, 0.0019, rng)).status,
            MouseMotionStatus::kLostTracking);
  EXPECT_EQ(odo.pose(), Pose2{});
  EXPECT_EQ(odo.lostIntervals(), 1);
  EXPECT_EQ(right.sample(inc, 0.01, 0.002, rng).status, MouseStatus::kTracking);  // at the limit
}

TEST(MouseSensor, RejectsInvalidSpecificationsAndInput) {
  MouseSensorSpec bad;
  bad.counts_per_inch = 0.0;
  EXPECT_THROW(MouseSensorSimulator(bad, {}), std::invalid_argument);
  MouseNoise noise;
  noise.relative_stddev = -0.1;
  EXPECT_THROW(MouseSensorSimulator({}, {}, noise), std::invalid_argument);
  MouseSensorSimulator sensor({}, {});
  SimRandom rng(1);
  EXPECT_THROW(sensor.sample({std::nan(""), 0.0, 0.0}, 0.01, 0.0, rng), std::invalid_argument);
  EXPECT_THROW(sensor.sample({0.0, 0.0, 0.0}, 0.0, 0.0, rng), std::invalid_argument);
  EXPECT_THROW(sensor.sample({1e20, 0.0, 0.0}, 1e300, 0.0, rng), std::invalid_argument);
  EXPECT_THROW(symmetricMouseRig(0.0), std::invalid_argument);
  EXPECT_THROW(MouseOdometry(symmetricMouseRig(0.2), {0.0, std::nan(""), 0.0}),
               std::invalid_argument);
  const TwoSensorMotion m =
      inferTwoSensorMotion(symmetricMouseRig(0.2), Vec2(std::nan(""), 0.0), Vec2(0.0, 0.0));
  EXPECT_EQ(m.status, MouseMotionStatus::kLostTracking);
}

TEST(MouseOdometry, ReportsTheRigidityResidualOfInconsistentReadings) {
  const MouseRig rig = symmetricMouseRig(0.2);
  // The sensors move apart sideways: no rigid motion does that.
  const TwoSensorMotion m = inferTwoSensorMotion(rig, Vec2(0.01, -0.002), Vec2(0.01, 0.002));
  EXPECT_NEAR(m.rigidity_residual_m, 0.004, kExact);
  // (6): sign(y_r - y_l) in the paper's frame = the forward difference, zero here.
  EXPECT_EQ(m.dtheta_rad, 0.0);
}

TEST(MouseOdometry, TheBundledType20ProfileDescribesThePapersSensors) {
  const RobotProfileResult loaded = loadRobotProfileFile(std::string(IRGS_SOURCE_DIR) +
                                                         "/resources/robots/mouse_type20_004.json");
  ASSERT_TRUE(loaded.ok());
  EXPECT_EQ(loaded.profile->drive.type, DriveType::kMouseSensor);
  const MouseRigResult rig = mouseRigFromProfile(*loaded.profile);
  ASSERT_TRUE(rig.rig.has_value()) << (rig.diagnostics.empty() ? "" : rig.diagnostics[0].message);
  EXPECT_DOUBLE_EQ(rig.rig->spec.counts_per_inch, 800.0);
  EXPECT_NEAR(rig.rig->spec.max_speed_mps, 0.5334, 1e-9);
  EXPECT_DOUBLE_EQ(rig.rig->spec.max_lift_m, 0.002);
  EXPECT_LT(rig.rig->right.y_m, 0.0);                          // right sensor on the right
  EXPECT_NEAR(rig.rig->left.y_m, -rig.rig->right.y_m, 1e-12);  // symmetric as in Fig. 3
  EXPECT_NEAR(rig.rig->separation_m(), 0.2, 1e-12);
  EXPECT_LT(loaded.profile->limits.max_speed_mps, rig.rig->spec.max_speed_mps);
}

TEST(MouseOdometry, AProfileWithoutSensorsIsADiagnosticNotACrash) {
  RobotProfile profile;
  EXPECT_FALSE(mouseRigFromProfile(profile).rig.has_value());
  profile.drive.extra["mouse_sensors"] = {{"right", {{"x_m", 0.0}, {"y_m", "a"}}}};
  const MouseRigResult r = mouseRigFromProfile(profile);
  EXPECT_FALSE(r.rig.has_value());
  EXPECT_GE(r.diagnostics.size(), 3u);  // y_m not a number, heading missing, left missing
}

}  // namespace
}  // namespace irgs
