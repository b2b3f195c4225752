#include "core/sim/gyro_sim.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "core/sim/simulator.hpp"
#include "sim_test_support.hpp"

namespace irgs {
namespace {

GyroErrorModel exactGyro() {
  GyroErrorModel m;
  m.enabled = true;
  return m;
}

// Drives a square robot through a fixed command sequence and returns every sample.
std::vector<TelemetrySample> drive(const SimConfig& config) {
  WorldMap map;
  map.walls.push_back(test::wall({3.0, -3.0}, {3.0, 3.0}));
  RobotProfile robot = test::squareRobot();
  robot.sonars.push_back(test::forwardSonar());
  SimConfig c = config;
  c.odometry.slip_stddev = 0.01;
  Simulator sim(map, robot, c);
  std::vector<TelemetrySample> samples;
  for (int k = 0; k < 400; ++k) {
    sim.setCommand({0.3, k < 200 ? 0.5 : -0.8});
    samples.push_back(sim.step());
  }
  return samples;
}

TEST(GyroSim, EnablingTheGyroLeavesEveryOtherSimulatorOutputBitIdentical) {
  SimConfig without;
  without.seed = 42;
  SimConfig with = without;
  with.gyro = autogyroErrorModel();
  const auto a = drive(without);
  const auto b = drive(with);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_FALSE(a[i].gyro.has_value());
    ASSERT_TRUE(b[i].gyro.has_value());
    EXPECT_EQ(a[i].true_pose, b[i].true_pose);
    EXPECT_EQ(a[i].odometry_pose, b[i].odometry_pose);
    EXPECT_EQ(a[i].left_ticks, b[i].left_ticks);
    EXPECT_EQ(a[i].right_ticks, b[i].right_ticks);
    ASSERT_EQ(a[i].sonar.size(), b[i].sonar.size());
    for (std::size_t k = 0; k < a[i].sonar.size(); ++k)
      EXPECT_EQ(a[i].sonar[k].range_m, b[i].sonar[k].range_m);
  }
}

TEST(GyroSim, SameSeedGivesIdenticalReadingsAndAnotherSeedDiffers) {
  SimConfig c;
  c.seed = 5;
  c.gyro = autogyroErrorModel();
  const auto a = drive(c);
  const auto b = drive(c);
  c.seed = 6;
  const auto other = drive(c);
  int differ = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].gyro->rate_radps, b[i].gyro->rate_radps);
    differ += a[i].gyro->rate_radps != other[i].gyro->rate_radps ? 1 : 0;
  }
  EXPECT_GT(differ, 300);
}

TEST(GyroSim, AnErrorFreeGyroReadsTheTrueTurnRate) {
  SimConfig c;
  c.gyro = exactGyro();
  Simulator sim(WorldMap{}, test::squareRobot(), c);
  sim.setCommand({0.2, 0.7});
  for (int k = 0; k < 300; ++k) {
    const TelemetrySample s = sim.step();
    EXPECT_NEAR(s.gyro->rate_radps, sim.trueVelocity().angular_radps, 1e-12);
    EXPECT_FALSE(s.gyro->saturated);
  }
}

TEST(GyroSim, TheCubicCorrectionOfTheIndicatedOutputGivesBackTheRate) {
  const GyroErrorModel m = autogyroErrorModel();
  for (double y : {-99.0, -20.0, -0.01, 0.0, 3.0, 95.0}) {
    const double x = gyroIndicatedDps(m, y);
    EXPECT_NEAR(x + gyroScaleCorrectionDps(m, x), y, 1e-12);
  }
  // The paper's cubic at 95 deg/s: about 3.6 deg/s (A001-6).
  EXPECT_NEAR(gyroScaleCorrectionDps(m, 95.0), 3.56, 0.02);
}

TEST(GyroSim, TemperatureWarmsUpAndMovesTheBiasAlongItsLine) {
  GyroErrorModel m = exactGyro();
  m.bias_c0_dps = -0.01;
  m.bias_c1_dps_per_c = 0.002;
  m.temperature_start_c = 20.0;
  m.temperature_end_c = 35.0;
  m.temperature_time_constant_s = 100.0;
  GyroSimulator gyro(m, SimRandom(1));
  const GyroReading early = gyro.read(0.0, 0.0, 0.1);
  const GyroReading late = gyro.read(0.0, 1000.0, 0.1);
  EXPECT_DOUBLE_EQ(early.temperature_c, 20.0);
  EXPECT_NEAR(late.temperature_c, 35.0, 1e-3);
  EXPECT_NEAR(radToDeg(early.rate_radps), 0.03, 1e-12);
  EXPECT_NEAR(radToDeg(late.rate_radps), 0.06, 1e-5);
}

TEST(GyroSim, RatesBeyondTheRangeClipAndAreFlaggedSaturated) {
  GyroSimulator gyro(autogyroErrorModel(), SimRandom(3));
  const GyroReading r = gyro.read(degToRad(150.0), 1.0, 0.01);
  EXPECT_TRUE(r.saturated);
  EXPECT_DOUBLE_EQ(r.rate_radps, degToRad(100.0));
  const GyroReading n = gyro.read(degToRad(-150.0), 1.0, 0.01);
  EXPECT_DOUBLE_EQ(n.rate_radps, degToRad(-100.0));
}

TEST(GyroSim, BiasDriftHasTheConfiguredStationaryStddev) {
  GyroErrorModel m = exactGyro();
  m.bias_instability_dps = 18.0 / 3600.0;
  m.bias_correlation_time_s = 10.0;
  double sum2 = 0.0;
  int n = 0;
  for (std::uint64_t seed = 0; seed < 40; ++seed) {
    GyroSimulator gyro(m, SimRandom(seed));
    for (int k = 0; k < 1000; ++k) {
      gyro.read(0.0, k * 1.0, 1.0);
      if (k % 50 == 0) {
        sum2 += gyro.driftBiasDps() * gyro.driftBiasDps();
        ++n;
      }
    }
  }
  EXPECT_NEAR(std::sqrt(sum2 / n), m.bias_instability_dps, 0.1 * m.bias_instability_dps);
}

TEST(GyroSim, InvalidModelsThrow) {
  GyroErrorModel m = autogyroErrorModel();
  m.range_dps = 0.0;
  EXPECT_THROW(GyroSimulator(m, SimRandom(1)), std::invalid_argument);
  m = autogyroErrorModel();
  m.sf_a1 = -2.0;  // x + p(x) decreasing: not invertible
  EXPECT_THROW(validate(m), std::invalid_argument);
  m = autogyroErrorModel();
  m.bias_instability_dps = std::nan("");
  SimConfig c;
  c.gyro = m;
  EXPECT_THROW(Simulator(WorldMap{}, test::squareRobot(), c), std::invalid_argument);
  GyroSimulator ok(autogyroErrorModel(), SimRandom(1));
  EXPECT_THROW(ok.read(std::nan(""), 0.0, 0.1), std::invalid_argument);
  EXPECT_THROW(ok.read(0.0, 0.0, 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace irgs
