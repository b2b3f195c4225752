#include "core/calibration/gyro_calibration_run.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace irgs {
namespace {

// Issue 6 acceptance: the simulated procedure recovers the injected coefficients within 10 %.
// The AUTOGYRO level of 001 (its cubic, our temperature line, its drift and noise).
TEST(GyroCalibrationRun, TheSimulatedProcedureRecoversTheInjectedCoefficientsWithinTenPercent) {
  const GyroErrorModel injected = autogyroErrorModel();
  GyroProcedureConfig config;
  config.seed = 5;
  const GyroProcedureResult r = runGyroCalibrationInSimulator(injected, config);
  ASSERT_TRUE(r.ok);
  EXPECT_GT(r.rate_samples, 1000u);
  EXPECT_GT(r.rest_samples, 100000u);
  EXPECT_NEAR(r.rest_min_temperature_c, 15.0, 0.5);
  EXPECT_NEAR(r.rest_max_temperature_c, 40.0, 0.5);
  const double mid = 0.5 * (r.rest_min_temperature_c + r.rest_max_temperature_c);
  for (const GyroCoefficientCheck& c : compareGyroCalibration(r.calibration, injected, 1, mid)) {
    RecordProperty(c.name, std::to_string(c.relative_error));
    if (c.name == "c0")
      continue;  // an extrapolation to 0 C: checked in absolute terms below
    EXPECT_LT(c.relative_error, 0.1)
        << c.name << ": injected " << c.injected << ", recovered " << c.recovered;
  }
  // c0 is off by at most the turn-on bias spread and the slope error times T_mid.
  EXPECT_NEAR(r.calibration.bias.c0_dps, injected.bias_c0_dps, 0.02);
}

TEST(GyroCalibrationRun, AQuadraticTemperatureBiasIsRecoveredByTheSecondOrderProcedure) {
  GyroErrorModel injected = autogyroErrorModel();
  injected.bias_c2_dps_per_c2 = -2e-4;
  GyroProcedureConfig config;
  config.runs.bias_order = 2;
  config.turn_ons = 2;
  const GyroProcedureResult r = runGyroCalibrationInSimulator(injected, config);
  ASSERT_TRUE(r.ok);
  const auto checks = compareGyroCalibration(r.calibration, injected, 2, 27.5);
  bool saw_c2 = false;
  for (const GyroCoefficientCheck& c : checks) {
    if (c.name == "c2") {
      saw_c2 = true;
      EXPECT_LT(c.relative_error, 0.1) << c.recovered;
    }
  }
  EXPECT_TRUE(saw_c2);
}

TEST(GyroCalibrationRun, LogsFromARealRobotAreFittedAndMissingRowsReported) {
  // A noise-free gyro written as the CSV a real bench produces.
  GyroErrorModel m = autogyroErrorModel();
  std::string table = "true_dps,indicated_dps\n";
  for (int w = -90; w <= 90; w += 10)
    table += std::to_string(w) + "," +
             std::to_string(gyroIndicatedDps(m, w + gyroTemperatureBiasDps(m, 25.0))) + "\n";
  std::string rest = "# chamber\ntemperature_c,indicated_dps\n";
  for (int t = 10; t <= 40; t += 5)
    rest += std::to_string(t) + "," +
            std::to_string(gyroIndicatedDps(m, gyroTemperatureBiasDps(m, t))) + "\nbad,row\n";
  const GyroProcedureResult r =
      fitGyroCalibrationLogs(parseCalibrationCsv(table), parseCalibrationCsv(rest), 1);
  ASSERT_TRUE(r.ok);
  EXPECT_NEAR(r.calibration.scale.a1, m.sf_a1, 1e-4);
  EXPECT_NEAR(r.calibration.bias.c1_dps_per_c, m.bias_c1_dps_per_c, 1e-5);
  EXPECT_FALSE(r.diagnostics.empty());  // the "bad,row" lines
  const GyroProcedureResult empty =
      fitGyroCalibrationLogs(parseCalibrationCsv(""), parseCalibrationCsv(""), 1);
  EXPECT_FALSE(empty.ok);
  EXPECT_GE(empty.diagnostics.size(), 2u);
  EXPECT_THROW(fitGyroCalibrationLogs({}, {}, 3), std::invalid_argument);
  GyroProcedureConfig bad;
  bad.turn_ons = 0;
  EXPECT_THROW(runGyroCalibrationInSimulator(m, bad), std::invalid_argument);
}

}  // namespace
}  // namespace irgs
