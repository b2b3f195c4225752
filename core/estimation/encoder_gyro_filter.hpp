#pragma once
// Encoder + gyro dead reckoning with the indirect feedback Kalman filter of paper 001_… (digest
// 2.4, 2.6; Fig. 10/11). The navigation solution is encoder dead reckoning through a corrected
// sensor model (wheel scale factors, wheelbase); a second heading phi is integrated from the
// calibrated gyro rate through a corrected gyro model (scale factor, bias). A 9-state linear
// error-state filter (dr_error_model.hpp) is propagated every step and updated with the heading
// difference Z = psi_enc - phi_gyro (A001-4); its estimate is fed back into the navigation
// solution and the sensor models, then reset to zero, so the error model stays linear.
//
// A consistency monitor (innovation test, covariance and correction bounds) switches the filter
// to a fall-back mode in which the published pose continues as plain encoder dead reckoning
// through the nominal model, from where the filter left it (the reason 001 prefers the feedback
// structure: the unfiltered pose is always there). Pure and deterministic.

#include <cstdint>
#include <optional>

#include "core/estimation/dr_error_model.hpp"
#include "core/geometry/types.hpp"

namespace irgs {

struct EncoderGyroFilterConfig {
  double wheelbase_m = 0.5;  // nominal D

  // Initial 1-sigma of the error states (001 gives no values; docs/dead-reckoning.md).
  double initial_position_stddev_m = 0.0;
  double initial_heading_stddev_rad = 0.0;                  // each of psi and phi
  double encoder_scale_stddev = 0.002;                      // S_R, S_L
  double wheelbase_stddev_m = 0.0025;                       // dD
  double gyro_scale_stddev = 0.002;                         // dB_s
  double gyro_bias_stddev_radps = degToRad(18.0 / 3600.0);  // dB_rb

  // Process noise w (001: "obtained experimentally", no values).
  double wheel_travel_variance_per_m = 1e-7;           // m^2 per metre of travel, per wheel
  double gyro_angle_random_walk_rad2_per_s = 1e-9;     // white rate noise, on dphi
  double gyro_bias_variance_rate_rad2_per_s3 = 1e-13;  // bias drift, on dB_rb
  // Measurement noise v on Z (encoder quantisation, timing), rad^2.
  double measurement_variance_rad2 = 1e-6;

  // Consistency monitor.
  double gate_nis = 10.83;              // chi^2(1) at 99.9 %: an innovation beyond is not applied
  int max_consecutive_gated = 50;       // ... and this many in a row means the filter misbehaves
  double max_heading_stddev_rad = 0.5;  // covariance blow-up
  double max_scale_correction = 0.05;   // |s_R|, |s_L|, |k_s|, |dD| / D beyond: implausible
  double max_gyro_bias_radps = degToRad(1.0);
  // Input plausibility: a step with more wheel travel or a faster gyro rate than this is
  // rejected as corrupt (no robot of ours moves 1 m in one step).
  double max_step_travel_m = 1.0;
  double max_gyro_rate_radps = 20.0;

  // Gyro bias subtracted from the calibrated rate at the start (the at-rest average, 001 2.6
  // step 1), rad/s.
  double initial_gyro_bias_radps = 0.0;
};

// Throws std::invalid_argument for non-finite or out-of-range values.
void validate(const EncoderGyroFilterConfig& config);

// One step of raw sensor data. Encoder increments are the nominal ones (ticks x metres per
// tick); the gyro rate is calibrated (temperature bias and cubic scale factor removed, (6)) and
// absent when the gyro gave nothing usable (missing or saturated).
struct DrStepInput {
  double right_m = 0.0;
  double left_m = 0.0;
  std::optional<double> gyro_rate_radps;
  double dt_s = 0.0;
};

enum class DrStepStatus {
  kUpdated,            // predicted, updated with Z, fed back
  kPredictedOnly,      // no gyro this step: predicted only
  kGated,              // the innovation failed the gate: predicted only
  kFallback,           // the filter is off; plain encoder dead reckoning
  kRejectedNonFinite,  // NaN/Inf, dt <= 0 or implausibly large input: nothing changed
};

enum class DrFilterMode { kFiltering, kFallback };
enum class DrFallbackReason {
  kNone,
  kInnovationTest,        // too many consecutive gated innovations
  kCovarianceBlowUp,      // heading stddev beyond the bound, or P not finite
  kImplausibleCorrection  // a fed-back sensor correction left its plausible range
};

struct DrStepResult {
  DrStepStatus status = DrStepStatus::kRejectedNonFinite;
  double innovation_rad = 0.0;  // Z (the predicted error state is zero after each reset)
  double innovation_variance = 0.0;
  double nis = 0.0;  // Z^2 / S
};

// The sensor model the navigation integrates with (the fed-back corrections).
struct DrSensorModel {
  double right_scale = 1.0;  // corrected increment = raw * scale
  double left_scale = 1.0;
  double wheelbase_m = 0.5;
  double gyro_scale = 1.0;  // used rate = gyro_scale * calibrated rate - gyro_bias
  double gyro_bias_radps = 0.0;
};

class EncoderGyroFilter {
 public:
  // Starts at `start` with the gyro heading equal to start.theta. Throws as validate().
  EncoderGyroFilter(const EncoderGyroFilterConfig& config, const Pose2& start);

  DrStepResult step(const DrStepInput& input);

  // Re-arms the filter after a fall-back: initial covariances, nominal sensor model except the
  // gyro bias (kept), gyro heading reset to the current pose's heading.
  void restart();

  // The navigation solution (fed back; plain encoder DR after a fall-back).
  const Pose2& pose() const { return pose_; }
  double gyroHeading() const { return gyro_heading_rad_; }
  // Open-loop encoder dead reckoning from the start through the nominal model, never corrected.
  const Pose2& unfilteredPose() const { return unfiltered_; }
  const DrCov& covariance() const { return p_; }
  const DrSensorModel& sensorModel() const { return model_; }
  DrFilterMode mode() const { return mode_; }
  DrFallbackReason fallbackReason() const { return reason_; }
  const EncoderGyroFilterConfig& config() const { return config_; }
  std::int64_t updateCount() const { return updates_; }
  std::int64_t gatedCount() const { return gated_; }

 private:
  DrCov initialCovariance() const;
  void fallBack(DrFallbackReason reason);
  bool healthy() const;

  EncoderGyroFilterConfig config_;
  DrSensorModel model_;
  Pose2 pose_;
  Pose2 unfiltered_;
  double gyro_heading_rad_ = 0.0;
  DrCov p_ = DrCov::Zero();
  DrFilterMode mode_ = DrFilterMode::kFiltering;
  DrFallbackReason reason_ = DrFallbackReason::kNone;
  int consecutive_gated_ = 0;
  std::int64_t updates_ = 0;
  std::int64_t gated_ = 0;
};

}  // namespace irgs
