#pragma once
// A single-axis rate gyro (yaw) for the simulator, modelled on the AUTOGYRO fibre-optic gyro of
// paper 001_… (digest 2.3, 2.7; reasons in docs/dead-reckoning.md).
//
// Forward model, deg/s (the paper's calibration units, A001-6). With w the true rate, T the
// temperature, the gyro's indicated output x solves
//   x + p(x) = (w + b_run + b_gm(t) + n) / (1 + s_run) + b(T)
//   p(x) = a3 x^3 + a2 x^2 + a1 x                        (6): the cubic scale-factor correction
//   b(T) = c0 + c1 T + c2 T^2                            the deterministic temperature bias
// so the paper's calibration "corrected = x + p(x) - b(T)" returns (w + b_run + b_gm + n) / (1 +
// s_run): exactly the random errors 001 leaves to its Kalman filter (random constant scale-factor
// error s_run and bias b_run drawn once per run, a Gauss-Markov bias drift b_gm, white rate noise
// n). The output clips at +/- range (the reading is then flagged saturated).
//
// Random numbers come from one SimRandom stream (random.hpp): deterministic for a seed.

#include <cstdint>

#include "core/robot/telemetry.hpp"
#include "core/sim/random.hpp"

namespace irgs {

struct GyroErrorModel {
  bool enabled = false;  // read by the Simulator only: disabled, samples carry no GyroReading

  // Deterministic, removable by calibration (gyro_calibration.hpp).
  double bias_c0_dps = 0.0;  // b(T): output at rest, deg/s
  double bias_c1_dps_per_c = 0.0;
  double bias_c2_dps_per_c2 = 0.0;
  double sf_a1 = 0.0;  // p(x), x in deg/s (paper defaults in autogyroErrorModel())
  double sf_a2_per_dps = 0.0;
  double sf_a3_per_dps2 = 0.0;

  // Temperature: exponential warm-up from start to end with the given time constant, plus an
  // optional sinusoidal cycle (a thermal chamber during calibration).
  double temperature_start_c = 25.0;
  double temperature_end_c = 25.0;
  double temperature_time_constant_s = 600.0;
  double temperature_cycle_amplitude_c = 0.0;
  double temperature_cycle_period_s = 0.0;  // 0: no cycle

  // Random, left to the filter.
  double turn_on_bias_stddev_dps = 0.0;    // b_run, constant within a run
  double scale_factor_stddev = 0.0;        // s_run, relative, constant within a run
  double bias_instability_dps = 0.0;       // stationary stddev of the Gauss-Markov drift b_gm
  double bias_correlation_time_s = 600.0;  // its correlation time
  double angle_random_walk_dps_per_sqrt_s = 0.0;  // white rate noise density

  double range_dps = 100.0;  // input range; outputs clip here (AUTOGYRO +/-100 deg/s)
};

// AUTOGYRO level (001 Table 1: +/-100 deg/s, bias drift 18 deg/h, scale-factor linearity < 0.5 %)
// with the paper's cubic (6) and a linear temperature bias of our choosing (001 gives none).
GyroErrorModel autogyroErrorModel();

// Throws std::invalid_argument for non-finite values, negative stddevs, a non-positive range or
// time constant, or a cubic p(x) whose x + p(x) is not increasing over the range (not invertible).
void validate(const GyroErrorModel& model);

// Gyro temperature at time t (s since the simulator started), deg C.
double gyroTemperatureC(const GyroErrorModel& model, double time_s);
// b(T), deg/s.
double gyroTemperatureBiasDps(const GyroErrorModel& model, double temperature_c);
// p(x), deg/s.
double gyroScaleCorrectionDps(const GyroErrorModel& model, double indicated_dps);
// The x with x + p(x) = y (Newton, monotone by validate()); not clipped to the range.
double gyroIndicatedDps(const GyroErrorModel& model, double compensated_dps);

class GyroSimulator {
 public:
  // Draws the run's random constants from `rng`. Throws as validate().
  GyroSimulator(const GyroErrorModel& model, SimRandom rng);

  // The reading for a step of dt_s ending at time_s during which the body turned at
  // true_rate_radps on average. Advances the bias drift by dt_s.
  GyroReading read(double true_rate_radps, double time_s, double dt_s);

  const GyroErrorModel& model() const { return model_; }
  // Truth, for tests and experiment reports (deg/s and relative).
  double runBiasDps() const { return run_bias_dps_; }
  double driftBiasDps() const { return drift_bias_dps_; }
  double runScaleFactor() const { return run_scale_; }

 private:
  GyroErrorModel model_;
  SimRandom rng_;
  double run_bias_dps_ = 0.0;
  double run_scale_ = 0.0;
  double drift_bias_dps_ = 0.0;
};

}  // namespace irgs
