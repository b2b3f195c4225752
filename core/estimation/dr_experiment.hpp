#pragma once
// The 001_… experiments in simulation (digest 2.7), shared by the tests and irgs-observability:
// * calibrateSimulatedGyro: a rate-table run (-95..95 deg/s in 5 deg/s steps at constant
//   temperature) and a stationary temperature-cycled run in the Simulator, fitted with
//   gyro_calibration.hpp.
// * runDrLoop: the ~120 m loop through 4 waypoints at 0.2 m/s. A Labmate-like robot (no sonars,
//   point body, empty world) with per-seed encoder scale-factor and wheelbase errors and an
//   AUTOGYRO-level gyro rests first (gyro bias averaged, 001 2.6 step 1), then a waypoint
//   controller drives it on the indirect feedback filter's pose (as 001's robot drove on its
//   navigation solution) while the unfiltered encoder DR is integrated alongside.

#include <cstdint>
#include <optional>
#include <vector>

#include "core/estimation/encoder_gyro_filter.hpp"
#include "core/estimation/gyro_calibration.hpp"
#include "core/geometry/types.hpp"
#include "core/robot/robot_profile.hpp"
#include "core/sim/gyro_sim.hpp"

namespace irgs {

struct GyroCalibrationRun {
  GyroCalibration calibration;
  ScaleFactorFit scale_fit;
  TemperatureBiasFit bias_fit;
  std::vector<RateTableSample> rate_table;  // every sample of the table run
  std::vector<RestSample> rest;             // every sample of the stationary run
};

struct GyroCalibrationRunConfig {
  double table_min_dps = -95.0;  // 001 Fig. 5: -95..95 deg/s, 5 deg/s steps
  double table_max_dps = 95.0;
  double table_step_dps = 5.0;
  double table_dwell_s = 2.0;  // per rate
  double table_temperature_c = 25.0;
  // Stationary run in a thermal chamber: the temperature cycles between mid -/+ amplitude so the
  // slow bias drift does not masquerade as a temperature effect (a single warm-up would).
  double rest_duration_s = 4.0 * 3600.0;
  double rest_temperature_mid_c = 27.5;
  double rest_temperature_amplitude_c = 12.5;
  double rest_temperature_period_s = 1800.0;
  double dt_s = 0.05;
  int bias_order = 1;  // 1: line (as 001), 2: quadratic
};

// Runs both calibration runs with `model` (its random errors included: they are another turn-on
// of the same gyro) and fits. Throws std::invalid_argument for an invalid model or config.
GyroCalibrationRun calibrateSimulatedGyro(const GyroErrorModel& model, std::uint64_t seed,
                                          const GyroCalibrationRunConfig& config = {});

// The robot of the loop experiment (TRC Labmate-like: wheelbase 0.5 m, no sensors but encoders).
RobotProfile drLoopRobot();
// Start (0, 0) then 4 waypoints; the loop closes back at the start: 120.0 m.
std::vector<Vec2> defaultLoopWaypoints();

struct DrLoopConfig {
  std::uint64_t seed = 1;
  double dt_s = 0.02;
  double speed_mps = 0.2;
  double turn_rate_radps = 0.3;
  std::vector<Vec2> waypoints = defaultLoopWaypoints();  // then back to (0, 0)
  double initial_rest_s = 60.0;                          // gyro bias averaged at rest before moving
  double waypoint_pause_s = 5.0;                         // stop at each waypoint before turning
  GyroErrorModel gyro = autogyroErrorModel();
  double encoder_scale_stddev = 0.001;    // S_R, S_L drawn per seed
  double wheelbase_error_stddev = 0.005;  // dD / D drawn per seed
  double wheel_slip_stddev = 0.002;       // relative random slip per step, per wheel
  // Gyro calibration the navigation uses; default: calibrateSimulatedGyro with a derived seed.
  std::optional<GyroCalibration> calibration;
  // Filter tuning; wheelbase_m and initial_gyro_bias_radps are set by the run. When
  // `derive_filter_noise` is true the initial stddevs and process noise follow the error model.
  EncoderGyroFilterConfig filter;
  bool derive_filter_noise = true;
  double trace_period_s = 1.0;
  double max_duration_s = 3600.0;
};

struct DrTracePoint {
  double time_s = 0.0;
  Pose2 truth;
  Pose2 filtered;
  Pose2 unfiltered;
  DrState sigma = DrState::Zero();  // sqrt(diag P)
};

struct DrLoopResult {
  bool completed = false;  // reached the start again within max_duration_s
  double duration_s = 0.0;
  double distance_m = 0.0;  // true path length
  Pose2 true_final;
  Pose2 filtered_final;
  Pose2 unfiltered_final;
  double return_to_start_m = 0.0;   // |true final position - start|
  double filtered_error_m = 0.0;    // |filtered - true| position at the end
  double unfiltered_error_m = 0.0;  // |unfiltered encoder DR - true| at the end
  double filtered_heading_error_rad = 0.0;
  double unfiltered_heading_error_rad = 0.0;
  // Truth of the run's errors and what the filter ended with.
  double true_right_scale_error = 0.0;  // S_R
  double true_left_scale_error = 0.0;   // S_L
  double true_wheelbase_error_m = 0.0;  // dD
  DrSensorModel final_model;
  DrFilterMode mode = DrFilterMode::kFiltering;
  DrFallbackReason fallback = DrFallbackReason::kNone;
  std::int64_t updates = 0;
  std::int64_t gated = 0;
  double mean_nis = 0.0;  // over the applied updates; about 1 for a consistent filter
  std::vector<DrTracePoint> trace;
};

// Throws std::invalid_argument for an invalid config (dt, speeds, no waypoints, ...).
DrLoopResult runDrLoop(const DrLoopConfig& config);

}  // namespace irgs
