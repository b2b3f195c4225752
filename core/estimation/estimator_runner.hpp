#pragma once
// Runs one localization estimator on a stream of simulator telemetry and exposes each step's
// result: the GUI's localization panel and `irgs-sim --localize` both drive it.
//
// Estimators (EstimatorKind):
//   * kDeadReckoning: encoder odometry only, propagated through the EKF's prediction (so it
//     has a covariance that grows without bound: the baseline every filter is judged against);
//   * kStereoEkf: the paper-000 EKF (ekf_localizer.hpp) predicted from the encoder increments
//     and updated with stereo-sonar echoes simulated on the map from the TRUE pose
//     (StereoEchoSimulator, own seeded stream), sensors fired every stereo_period_s;
//   * kEncoderGyro: the paper-001 indirect feedback filter (encoder_gyro_filter.hpp) on the
//     encoder increments and the sample's gyro reading, calibrated with gyro_calibration;
//   * kMouseOdometry: the paper-004 two-sensor optical-mouse odometry (mouse_odometry.hpp) on the
//     sample's floor-sensor counts, the rig from the profile's drive/mouse_sensors; its
//     covariance is the encoder DR noise model applied to the same motion (004 gives none).
//   * kStereoEkfCaster: the paper-000 EKF on its own robot (drive type "three_caster"):
//     predicted with the least-squares J+ odometry (33) from the sample's six caster encoders,
//     with the adaptive process noise Q = caster_lambda ||e|| (36)-(37), in dead-reckoning
//     periods of caster_period_s [000: 1 ms] (the interval between two samples is split into
//     equal periods, encoder rates constant in between); updated like kStereoEkf. When the
//     samples carry the robot's own per-period residuals (CasterEncoders::residual_periods
//     grew), each period's ||e|| is the robot's mean over the interval instead of the residual
//     of the re-split counts, which averages slip and quantisation out at coarse sample rates
//     (docs/localization.md); otherwise (older recordings, robots that do not report it) the
//     re-split residual. Its dead reckoning is the same J+ prediction without updates. The
//     wheel-encoder kinds refuse a three-caster profile (it has no left/right wheels) and this one
//     refuses any other.
//
// Every sample is used once, in order: the encoder increment is the tick difference to the
// previous sample times the profile's metres per tick (nominal model, like the robot's own
// odometry). A tick jump beyond max_step_travel_m or a time that goes backwards (a new robot)
// re-baselines without predicting and is reported in the step's note. Stereo echoes need the
// true pose: a sample without it (a linked robot) predicts only. Pure and deterministic.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/estimation/ekf_localizer.hpp"
#include "core/estimation/encoder_gyro_filter.hpp"
#include "core/estimation/gyro_calibration.hpp"
#include "core/estimation/mouse_odometry.hpp"
#include "core/estimation/stereo_echo_sim.hpp"
#include "core/robot/robot_profile.hpp"
#include "core/robot/telemetry.hpp"
#include "core/sim/gyro_sim.hpp"
#include "core/world/world_map.hpp"

namespace irgs {

enum class EstimatorKind {
  kDeadReckoning,
  kStereoEkf,
  kEncoderGyro,
  kMouseOdometry,
  kStereoEkfCaster
};
inline constexpr EstimatorKind kAllEstimatorKinds[] = {
    EstimatorKind::kStereoEkf, EstimatorKind::kDeadReckoning, EstimatorKind::kEncoderGyro,
    EstimatorKind::kMouseOdometry, EstimatorKind::kStereoEkfCaster};

// The kinds that update with simulated stereo echoes (kStereoEkf, kStereoEkfCaster).
bool usesStereo(EstimatorKind kind);

// "dr", "ekf", "encoder-gyro", "mouse", "ekf-caster" (the irgs-sim --localize names).
const char* toString(EstimatorKind kind);
std::optional<EstimatorKind> parseEstimatorKind(std::string_view name);
// Human-readable, for menus and plots: "Dead reckoning", "Stereo-sonar EKF (000)", ...
const char* displayName(EstimatorKind kind);

// The stereo sensors of the 000 runs: right, left (at +/-0.2 m, looking sideways) and front.
std::vector<StereoSensor> defaultStereoSensors();

// The calibration that removes exactly the deterministic part of a simulated gyro (temperature
// bias and cubic scale factor): the random turn-on bias, scale factor and drift are left to the
// filter, as after a perfect 001 calibration run.
GyroCalibration idealGyroCalibration(const GyroErrorModel& model);

struct EstimatorRunnerConfig {
  EstimatorKind kind = EstimatorKind::kStereoEkf;
  // Initial 1-sigma of the estimator's belief about the start pose (EKF and DR).
  double initial_position_stddev_m = 0.05;
  double initial_heading_stddev_rad = degToRad(2.0);
  DiffDriveNoise process = {2e-4, LocCov::Zero()};  // EKF/DR prediction noise
  EkfLocalizerConfig ekf;
  std::vector<StereoSensor> sensors = defaultStereoSensors();
  StereoSonarParams sonar;
  StereoEchoNoise echo_noise = {0.002, 0.001, 0.05, degToRad(30.0), 0.2};
  double stereo_period_s = 0.04;                    // 000: one reading per sensor every 40 ms
  std::uint64_t seed = 1;                           // echo noise and dropouts
  EncoderGyroFilterConfig encoder_gyro;             // wheelbase_m is taken from the profile
  std::optional<GyroCalibration> gyro_calibration;  // empty: the raw gyro rate is used
  double max_step_travel_m = 1.0;     // a larger tick jump between samples is a discontinuity
  std::optional<MouseRig> mouse_rig;  // kMouseOdometry; empty: the profile's drive/mouse_sensors
  // kStereoEkfCaster: Q = caster_lambda ||e|| I6 per period (36) [000: 0.005; see
  // docs/localization.md for what it does with our wheel errors], the dead-reckoning period,
  // and the geometry (empty: the profile's drive/three_caster).
  double caster_lambda = 0.005;
  double caster_period_s = 0.001;
  std::optional<CasterDriveGeometry> caster_geometry;
  // Use the robot's reported J+ residual for Q when the samples carry it (false: always the
  // residual of the re-split counts, the behaviour before robots reported it).
  bool caster_robot_residual = true;
};

// Throws std::invalid_argument for non-finite or non-positive stddevs/periods, no sensors, or
// what the EKF/filter/echo-simulator validation throws.
void validate(const EstimatorRunnerConfig& config);

// One stereo reading of one sensor and what the EKF did with it.
struct StereoReadingRecord {
  std::size_t sensor = 0;  // index into EstimatorRunnerConfig::sensors
  EchoStatus echo = EchoStatus::kNoReflector;
  std::string true_reflector_id;  // the reflector the simulator bounced off (truth)
  LocalizationUpdate update;      // status kRejectedNonFinite when there was no echo
  bool accepted = false;          // at least one scalar update applied
};

struct EstimatorStep {
  double time_s = 0.0;
  std::int64_t index = 0;  // samples fed since the last reset
  bool predicted = false;  // false for the baseline sample and after a discontinuity
  std::optional<Pose2> truth;
  Pose2 estimate;
  LocCov covariance = LocCov::Zero();           // of (x, y, theta), world frame
  Pose2 dead_reckoning;                         // encoder DR through the nominal model, same start
  std::vector<StereoReadingRecord> readings;    // kStereoEkf: the readings taken at this sample
  std::optional<DrStepResult> encoder_gyro;     // kEncoderGyro: the filter's step
  std::optional<TwoSensorMotion> mouse_motion;  // kMouseOdometry: this interval's inference
  // kStereoEkfCaster: J+ periods predicted this sample and the sum of their residuals ||e||.
  int caster_periods = 0;
  double caster_residual_sum = 0.0;
  bool caster_residual_from_robot = false;  // ||e|| was the robot's reported mean residual
  // Error estimate - truth (x, y, wrapped theta) and NEES e' P^-1 e, when truth is known and P
  // is positive definite.
  std::optional<LocState> error;
  std::optional<double> nees;
  std::string note;  // why the step did not predict, empty otherwise
};

// Running metrics over the steps with truth (the first, baseline step included).
struct EstimatorMetrics {
  std::int64_t steps = 0;  // with truth
  double duration_s = 0.0;
  double distance_m = 0.0;  // true path length
  double rms_position_error_m = 0.0;
  double rms_heading_error_rad = 0.0;
  double max_position_error_m = 0.0;
  double final_position_error_m = 0.0;
  double final_heading_error_rad = 0.0;
  double dr_rms_position_error_m = 0.0;
  double dr_final_position_error_m = 0.0;
  double dr_final_heading_error_rad = 0.0;
  std::int64_t nees_steps = 0;
  double mean_nees = 0.0;
  double nees_within_95 = 0.0;  // fraction of nees_steps below chi2(3) 95 % = 7.815
  // Stereo echoes received (kStereoEkf) / gyro samples / floor-sensor readings (kMouseOdometry).
  std::int64_t readings = 0;
  std::int64_t accepted = 0;  // applied updates / readings with both sensors tracking
  // kStereoEkfCaster: J+ periods predicted and their mean least-squares residual ||e|| (rad).
  std::int64_t caster_periods = 0;
  double mean_caster_residual_rad = 0.0;
  double acceptedFraction() const {
    return readings > 0 ? static_cast<double>(accepted) / static_cast<double>(readings) : 0.0;
  }
};

inline constexpr double kChi2Dof3P95 = 7.815;

class EstimatorRunner {
 public:
  // Throws std::invalid_argument for an invalid config, a non-finite initial pose, a profile
  // with a non-positive wheelbase or metres per tick, or (kMouseOdometry) no mouse rig.
  EstimatorRunner(const WorldMap& map, const RobotProfile& profile, const Pose2& initial_estimate,
                  EstimatorRunnerConfig config);

  // Restarts the estimator at `initial_estimate` (metrics and the echo stream too); the next
  // sample is a new baseline. Throws std::invalid_argument for a non-finite pose.
  void reset(const Pose2& initial_estimate);

  // Processes one sample (see the file comment) and returns its step (valid until the next
  // call). Samples with a non-finite time are ignored (the previous step is returned, with a
  // note).
  const EstimatorStep& feed(const TelemetrySample& sample);

  const EstimatorStep& lastStep() const { return step_; }
  const EstimatorMetrics& metrics() const { return metrics_; }
  const EstimatorRunnerConfig& config() const { return config_; }
  const LocalizationMap& localizationMap() const { return loc_map_; }
  EstimatorKind kind() const { return config_.kind; }
  const Pose2& initialEstimate() const { return initial_; }

 private:
  void finishStep(const TelemetrySample& sample);
  void fireStereo(const Pose2& truth);
  void predictFromMice(const TelemetrySample& sample);
  void predictFromCasters(const TelemetrySample& sample, double dt);
  bool casterJump(const CasterEncoders& before, const CasterEncoders& now) const;
  bool isCasterKind() const { return config_.kind == EstimatorKind::kStereoEkfCaster; }
  void currentEstimate();

  EstimatorRunnerConfig config_;
  LocalizationMap loc_map_;
  StereoEchoSimulator echoes_;
  double metres_per_tick_ = 0.0;
  double wheelbase_m_ = 0.0;
  Pose2 initial_;

  EkfLocalizer ekf_;  // kStereoEkf and kDeadReckoning (prediction only)
  std::optional<EncoderGyroFilter> encoder_gyro_;
  std::optional<MouseOdometry> mouse_;      // kMouseOdometry
  std::optional<MouseReading> last_mouse_;  // the previous sample's cumulative counts
  double caster_ticks_per_rad_ = 0.0;
  EkfLocalizer caster_dr_;                      // kStereoEkfCaster: J+ prediction only
  std::optional<CasterEncoders> last_casters_;  // the previous sample's encoders
  double caster_residual_total_ = 0.0;
  SimRandom echo_rng_;

  bool has_baseline_ = false;
  std::int64_t last_left_ = 0;
  std::int64_t last_right_ = 0;
  double last_time_s_ = 0.0;
  double next_echo_s_ = 0.0;
  std::optional<Pose2> last_truth_;
  double first_truth_time_s_ = 0.0;

  EstimatorStep step_;
  EstimatorMetrics metrics_;
  double sum_sq_pos_ = 0.0;
  double sum_sq_heading_ = 0.0;
  double sum_sq_dr_ = 0.0;
  double sum_nees_ = 0.0;
  std::int64_t nees_within_ = 0;
};

}  // namespace irgs
