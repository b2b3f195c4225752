#include "core/calibration/gyro_calibration_run.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/sim/random.hpp"

namespace irgs {

namespace {

void finishFits(GyroProcedureResult& r, int bias_order) {
  r.rate_samples = r.scale_fit.used;
  r.rest_samples = r.bias_fit.used;
  for (const std::string& d : r.scale_fit.diagnostics)
    r.diagnostics.push_back("rate table: " + d);
  for (const std::string& d : r.bias_fit.diagnostics)
    r.diagnostics.push_back("stationary: " + d);
  r.calibration.scale = r.scale_fit.curve;
  r.calibration.bias = r.bias_fit.bias;
  if (bias_order == 1)
    r.calibration.bias.c2_dps_per_c2 = 0.0;
  r.ok = r.scale_fit.ok && r.bias_fit.ok;
}

void temperatureRange(GyroProcedureResult& r, const std::vector<RestSample>& rest) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const RestSample& s : rest) {
    if (!std::isfinite(s.temperature_c))
      continue;
    lo = std::min(lo, s.temperature_c);
    hi = std::max(hi, s.temperature_c);
  }
  if (lo <= hi) {
    r.rest_min_temperature_c = lo;
    r.rest_max_temperature_c = hi;
  }
}

}  // namespace

GyroProcedureResult runGyroCalibrationInSimulator(const GyroErrorModel& injected,
                                                  const GyroProcedureConfig& config) {
  if (config.turn_ons < 1 || config.turn_ons > 50)
    throw std::invalid_argument("runGyroCalibrationInSimulator: turn_ons must be in 1..50");
  std::vector<RateTableSample> table;
  std::vector<RestSample> rest;
  for (int i = 0; i < config.turn_ons; ++i) {
    // Each power-up its own seed: new turn-on bias, run scale factor, drift and noise.
    const GyroCalibrationRun run = calibrateSimulatedGyro(
        injected, splitMix64(config.seed + static_cast<std::uint64_t>(i)), config.runs);
    table.insert(table.end(), run.rate_table.begin(), run.rate_table.end());
    rest.insert(rest.end(), run.rest.begin(), run.rest.end());
  }
  GyroProcedureResult r;
  r.scale_fit = fitScaleFactorCurve(table);
  r.bias_fit = fitTemperatureBias(rest, config.runs.bias_order, r.scale_fit.curve);
  temperatureRange(r, rest);
  finishFits(r, config.runs.bias_order);
  return r;
}

GyroProcedureResult fitGyroCalibrationLogs(const CalibrationLog& rate_table_log,
                                           const CalibrationLog& stationary_log, int bias_order) {
  if (bias_order != 1 && bias_order != 2)
    throw std::invalid_argument("fitGyroCalibrationLogs: bias order must be 1 or 2");
  GyroProcedureResult r;
  for (const std::string& d : rate_table_log.diagnostics)
    r.diagnostics.push_back("rate table log: " + d);
  for (const std::string& d : stationary_log.diagnostics)
    r.diagnostics.push_back("stationary log: " + d);
  if (rate_table_log.rate_table.empty())
    r.diagnostics.push_back("the rate-table log has no true_dps,indicated_dps rows");
  if (stationary_log.rest.empty())
    r.diagnostics.push_back("the stationary log has no temperature_c,indicated_dps rows");
  r.scale_fit = fitScaleFactorCurve(rate_table_log.rate_table);
  r.bias_fit = fitTemperatureBias(stationary_log.rest, bias_order, r.scale_fit.curve);
  temperatureRange(r, stationary_log.rest);
  finishFits(r, bias_order);
  return r;
}

std::vector<GyroCoefficientCheck> compareGyroCalibration(const GyroCalibration& recovered,
                                                         const GyroErrorModel& injected,
                                                         int bias_order, double mid_temperature_c) {
  auto check = [](std::string name, double truth, double got) {
    const double err = std::abs(got - truth);
    return GyroCoefficientCheck{std::move(name), truth, got,
                                truth != 0.0 ? err / std::abs(truth) : err};
  };
  std::vector<GyroCoefficientCheck> out;
  out.push_back(check("a1", injected.sf_a1, recovered.scale.a1));
  out.push_back(check("a2", injected.sf_a2_per_dps, recovered.scale.a2_per_dps));
  out.push_back(check("a3", injected.sf_a3_per_dps2, recovered.scale.a3_per_dps2));
  out.push_back(check("c1", injected.bias_c1_dps_per_c, recovered.bias.c1_dps_per_c));
  if (bias_order == 2)
    out.push_back(check("c2", injected.bias_c2_dps_per_c2, recovered.bias.c2_dps_per_c2));
  out.push_back(check("b(T_mid)", gyroTemperatureBiasDps(injected, mid_temperature_c),
                      recovered.bias.at(mid_temperature_c)));
  out.push_back(check("c0", injected.bias_c0_dps, recovered.bias.c0_dps));
  return out;
}

}  // namespace irgs
