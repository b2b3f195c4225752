#include "core/sim/gyro_sim.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace irgs {

namespace {

void require(bool condition, const std::string& what) {
  if (!condition)
    throw std::invalid_argument("GyroErrorModel: " + what);
}

bool finite(double v) {
  return std::isfinite(v);
}

// d/dx (x + p(x)).
double slope(const GyroErrorModel& m, double x) {
  return 1.0 + m.sf_a1 + 2.0 * m.sf_a2_per_dps * x + 3.0 * m.sf_a3_per_dps2 * x * x;
}

}  // namespace

GyroErrorModel autogyroErrorModel() {
  GyroErrorModel m;
  m.enabled = true;
  // Our temperature bias line: 0.03 deg/s at 20 C rising 0.002 deg/s per C (001 fits a line but
  // prints no coefficients); the warm-up 20 -> 35 C is what a gyro sees after switch-on.
  m.bias_c0_dps = -0.01;
  m.bias_c1_dps_per_c = 0.002;
  m.temperature_start_c = 20.0;
  m.temperature_end_c = 35.0;
  m.temperature_time_constant_s = 600.0;
  // (6) [001]: a3 = 2.71e-6, a2 = 7.05e-6, a1 = 0.01252, x in deg/s (A001-6 reading).
  m.sf_a1 = 0.012520;
  m.sf_a2_per_dps = 0.00000705;
  m.sf_a3_per_dps2 = 0.00000271;
  // Table 1: bias drift 18 deg/h (turn-on spread and Gauss-Markov drift). Table 1's "linearity
  // < 0.5 %" is the deterministic shape the cubic removes; the run-to-run scale-factor error left
  // after calibration is not given: 0.1 % (1000 ppm), a typical FOG repeatability, is our choice
  // (docs/dead-reckoning.md shows how the loop error depends on it).
  m.turn_on_bias_stddev_dps = 18.0 / 3600.0;
  m.bias_instability_dps = 18.0 / 3600.0;
  m.bias_correlation_time_s = 600.0;
  m.scale_factor_stddev = 0.001;
  m.angle_random_walk_dps_per_sqrt_s = 0.1 / 60.0;  // 0.1 deg/sqrt(h), typical of FOGs
  m.range_dps = 100.0;
  return m;
}

void validate(const GyroErrorModel& m) {
  require(finite(m.bias_c0_dps) && finite(m.bias_c1_dps_per_c) && finite(m.bias_c2_dps_per_c2),
          "bias coefficients must be finite");
  require(finite(m.sf_a1) && finite(m.sf_a2_per_dps) && finite(m.sf_a3_per_dps2),
          "scale-factor coefficients must be finite");
  require(finite(m.temperature_start_c) && finite(m.temperature_end_c),
          "temperatures must be finite");
  require(finite(m.temperature_time_constant_s) && m.temperature_time_constant_s > 0.0,
          "temperature_time_constant_s must be > 0");
  require(finite(m.temperature_cycle_amplitude_c) && finite(m.temperature_cycle_period_s) &&
              m.temperature_cycle_period_s >= 0.0,
          "temperature cycle must be finite with a period >= 0");
  require(finite(m.turn_on_bias_stddev_dps) && m.turn_on_bias_stddev_dps >= 0.0 &&
              finite(m.scale_factor_stddev) && m.scale_factor_stddev >= 0.0 &&
              m.scale_factor_stddev < 0.5 && finite(m.bias_instability_dps) &&
              m.bias_instability_dps >= 0.0 && finite(m.angle_random_walk_dps_per_sqrt_s) &&
              m.angle_random_walk_dps_per_sqrt_s >= 0.0,
          "random error stddevs must be finite and >= 0 (scale factor < 0.5)");
  require(finite(m.bias_correlation_time_s) && m.bias_correlation_time_s > 0.0,
          "bias_correlation_time_s must be > 0");
  require(finite(m.range_dps) && m.range_dps > 0.0, "range_dps must be > 0");
  // x + p(x) must increase over twice the range (outputs are clipped at the range, but the
  // inversion searches a little beyond it).
  const double r = 2.0 * m.range_dps;
  const double min_slope =
      std::min({slope(m, -r), slope(m, r), slope(m, 0.0),
                m.sf_a3_per_dps2 != 0.0
                    ? slope(m, std::clamp(-m.sf_a2_per_dps / (3.0 * m.sf_a3_per_dps2), -r, r))
                    : 1.0});
  require(min_slope > 0.1, "x + p(x) must increase with x over the range");
}

double gyroTemperatureC(const GyroErrorModel& m, double time_s) {
  const double t = std::max(0.0, time_s);
  double temperature = m.temperature_end_c + (m.temperature_start_c - m.temperature_end_c) *
                                                 std::exp(-t / m.temperature_time_constant_s);
  if (m.temperature_cycle_period_s > 0.0)
    temperature +=
        m.temperature_cycle_amplitude_c * std::sin(2.0 * kPi * t / m.temperature_cycle_period_s);
  return temperature;
}

double gyroTemperatureBiasDps(const GyroErrorModel& m, double temperature_c) {
  return m.bias_c0_dps +
         temperature_c * (m.bias_c1_dps_per_c + temperature_c * m.bias_c2_dps_per_c2);
}

double gyroScaleCorrectionDps(const GyroErrorModel& m, double x) {
  return x * (m.sf_a1 + x * (m.sf_a2_per_dps + x * m.sf_a3_per_dps2));
}

double gyroIndicatedDps(const GyroErrorModel& m, double y) {
  // Newton on g(x) = x + p(x) - y from x = y / (1 + a1); g is increasing (validate), so a few
  // steps reach machine precision for any rate a gyro can see.
  double x = y / (1.0 + m.sf_a1);
  for (int i = 0; i < 30; ++i) {
    const double step = (x + gyroScaleCorrectionDps(m, x) - y) / slope(m, x);
    x -= step;
    if (std::abs(step) <= 1e-15 * (1.0 + std::abs(x)))
      break;
  }
  return x;
}

GyroSimulator::GyroSimulator(const GyroErrorModel& model, SimRandom rng)
    : model_(model), rng_(rng) {
  validate(model_);
  // Fixed draw order: run bias, run scale factor, initial drift (stationary).
  run_bias_dps_ = model_.turn_on_bias_stddev_dps * rng_.gaussian();
  run_scale_ = model_.scale_factor_stddev * rng_.gaussian();
  drift_bias_dps_ = model_.bias_instability_dps * rng_.gaussian();
}

GyroReading GyroSimulator::read(double true_rate_radps, double time_s, double dt_s) {
  if (!std::isfinite(true_rate_radps) || !std::isfinite(time_s) || !std::isfinite(dt_s) ||
      dt_s <= 0.0)
    throw std::invalid_argument("GyroSimulator::read: non-finite rate/time or dt <= 0");
  // First-order Gauss-Markov drift, exact discretisation: b <- phi b + sigma sqrt(1 - phi^2) w.
  const double phi = std::exp(-dt_s / model_.bias_correlation_time_s);
  drift_bias_dps_ = phi * drift_bias_dps_ +
                    model_.bias_instability_dps * std::sqrt(1.0 - phi * phi) * rng_.gaussian();
  // White rate noise averaged over the step: stddev = ARW / sqrt(dt).
  const double noise_dps =
      model_.angle_random_walk_dps_per_sqrt_s / std::sqrt(dt_s) * rng_.gaussian();

  const double temperature = gyroTemperatureC(model_, time_s);
  const double w_dps = radToDeg(true_rate_radps);
  const double y = (w_dps + run_bias_dps_ + drift_bias_dps_ + noise_dps) / (1.0 + run_scale_) +
                   gyroTemperatureBiasDps(model_, temperature);
  double x = gyroIndicatedDps(model_, y);
  GyroReading reading;
  reading.temperature_c = temperature;
  if (std::abs(x) >= model_.range_dps) {
    x = std::copysign(model_.range_dps, x);
    reading.saturated = true;
  }
  reading.rate_radps = degToRad(x);
  return reading;
}

}  // namespace irgs
