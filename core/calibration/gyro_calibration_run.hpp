#pragma once
// The gyro calibration procedure of paper 001_… (digest 2.3) as a wizard runs it, in the
// simulator with a known injected gyro, or from logs recorded on a real robot.
//
// Simulated: `turn_ons` power-ups of the same gyro (each with its own turn-on bias and run
// scale factor, as on the bench), each giving a rate-table run (-95..95 deg/s, 001 Fig. 5) and a
// stationary run in a temperature-cycled chamber (calibrateSimulatedGyro, dr_experiment.hpp).
// The samples of all power-ups are pooled and fitted once with the existing least-squares fits
// (gyro_calibration.hpp): the cubic (6) first, then the temperature bias line/quadratic on
// x + p(x). Pooling averages the per-run random errors that no calibration can remove (turn-on
// bias, run scale factor) over the power-ups.

#include <cstdint>
#include <string>
#include <vector>

#include "core/estimation/dr_experiment.hpp"
#include "core/estimation/gyro_calibration.hpp"
#include "core/sim/gyro_sim.hpp"

namespace irgs {

struct GyroProcedureConfig {
  int turn_ons = 4;               // power-ups pooled (1..50)
  GyroCalibrationRunConfig runs;  // each power-up's table and stationary runs, bias order
  std::uint64_t seed = 1;
};

struct GyroProcedureResult {
  bool ok = false;  // both fits succeeded
  GyroCalibration calibration;
  ScaleFactorFit scale_fit;
  TemperatureBiasFit bias_fit;
  std::size_t rate_samples = 0;
  std::size_t rest_samples = 0;
  double rest_min_temperature_c = 0.0;
  double rest_max_temperature_c = 0.0;
  std::vector<std::string> diagnostics;
};

// Throws std::invalid_argument for an invalid model (validate()) or config.
GyroProcedureResult runGyroCalibrationInSimulator(const GyroErrorModel& injected,
                                                  const GyroProcedureConfig& config = {});

// The same fits on logs from a real robot (parseCalibrationCsv). Throws std::invalid_argument
// for a bias order other than 1 or 2.
GyroProcedureResult fitGyroCalibrationLogs(const CalibrationLog& rate_table_log,
                                           const CalibrationLog& stationary_log, int bias_order);

// One coefficient, injected vs recovered. relative_error = |recovered - injected| / |injected|
// (absolute error when the injected value is 0).
struct GyroCoefficientCheck {
  std::string name;  // "a1", "a2", "a3", "c1", "c2", "b(T_mid)", "c0"
  double injected = 0.0;
  double recovered = 0.0;
  double relative_error = 0.0;
};
// a1, a2, a3 (the cubic), c1 (and c2 when bias_order is 2), the bias at the middle of the
// calibrated temperature range b(T_mid), and c0 (the intercept at 0 C, an extrapolation outside
// the chamber's range, so it carries the slope's error times T_mid and the turn-on bias).
std::vector<GyroCoefficientCheck> compareGyroCalibration(const GyroCalibration& recovered,
                                                         const GyroErrorModel& injected,
                                                         int bias_order, double mid_temperature_c);

}  // namespace irgs
