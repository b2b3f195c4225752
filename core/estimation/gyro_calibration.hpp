#pragma once
// Gyro calibration of paper 001_… (digest 2.3): a temperature-bias line or quadratic fitted to
// a stationary run, and the cubic scale-factor correction (6) y = a3 x^3 + a2 x^2 + a1 x + Bias
// fitted to a rate-table run, both by least squares. Units as in the paper's reading of (6)
// (A001-6): x = indicated rate in deg/s, y = correction (true - indicated) in deg/s.
//
// Calibrated rate = x + p(x) - b(T), p(x) = a3 x^3 + a2 x^2 + a1 x, b(T) = c0 + c1 T + c2 T^2:
// b(T) is the gyro's output at rest after the cubic correction, so the two fits are done in
// order: the cubic first (its constant term is the table-temperature bias, kept for reference),
// then the bias on x + p(x) of the stationary run.

#include <span>
#include <string>
#include <vector>

namespace irgs {

struct TemperatureBias {
  double c0_dps = 0.0;
  double c1_dps_per_c = 0.0;
  double c2_dps_per_c2 = 0.0;  // zero for the line
  double at(double temperature_c) const {
    return c0_dps + temperature_c * (c1_dps_per_c + temperature_c * c2_dps_per_c2);
  }
};

struct ScaleFactorCurve {
  double a1 = 0.0;
  double a2_per_dps = 0.0;
  double a3_per_dps2 = 0.0;
  double bias_dps = 0.0;  // (6)'s "Bias" at the rate table's temperature; not used by compensate
  double correction(double indicated_dps) const {
    const double x = indicated_dps;
    return x * (a1 + x * (a2_per_dps + x * a3_per_dps2));
  }
};

struct GyroCalibration {
  TemperatureBias bias;
  ScaleFactorCurve scale;
  // x + p(x) - b(T), deg/s.
  double compensateDps(double indicated_dps, double temperature_c) const {
    return indicated_dps + scale.correction(indicated_dps) - bias.at(temperature_c);
  }
  double compensateRadps(double indicated_radps, double temperature_c) const;
};

// A rate-table sample: the table's true rate and the gyro's indicated output, deg/s.
struct RateTableSample {
  double true_dps = 0.0;
  double indicated_dps = 0.0;
};
// A stationary sample: temperature and indicated output at rest, deg/s.
struct RestSample {
  double temperature_c = 0.0;
  double indicated_dps = 0.0;
};

// Expected failures are values: `ok` false with diagnostics (too few distinct points, singular
// system); non-finite samples are skipped and counted.
struct ScaleFactorFit {
  bool ok = false;
  ScaleFactorCurve curve;
  double rms_residual_dps = 0.0;
  std::size_t used = 0;
  std::size_t skipped = 0;
  std::vector<std::string> diagnostics;
};
struct TemperatureBiasFit {
  bool ok = false;
  TemperatureBias bias;
  double rms_residual_dps = 0.0;
  std::size_t used = 0;
  std::size_t skipped = 0;
  std::vector<std::string> diagnostics;
};

// (6) by least squares: true - indicated = a3 x^3 + a2 x^2 + a1 x + Bias.
ScaleFactorFit fitScaleFactorCurve(std::span<const RateTableSample> samples);

// b(T) of order 1 (line, as 001 uses) or 2 (quadratic) on x + curve.correction(x).
// Throws std::invalid_argument for another order.
TemperatureBiasFit fitTemperatureBias(std::span<const RestSample> samples, int order,
                                      const ScaleFactorCurve& curve);

// Reads a calibration log: a header line naming the columns (any order, extra columns ignored)
// then one sample per line, comma separated; lines starting with '#' are comments. A log with a
// true_dps column is a rate-table run (true_dps, indicated_dps); otherwise it is a stationary
// run (temperature_c, indicated_dps). Unreadable rows are skipped with a diagnostic.
struct CalibrationLog {
  std::vector<RateTableSample> rate_table;  // rows with a true_dps column
  std::vector<RestSample> rest;             // rows with a temperature_c column
  std::vector<std::string> diagnostics;     // "line N: ..." for rows that could not be read
};
CalibrationLog parseCalibrationCsv(const std::string& text);

}  // namespace irgs
