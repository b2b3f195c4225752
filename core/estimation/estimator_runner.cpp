#include "core/estimation/estimator_runner.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/estimation/caster_profile.hpp"
#include "core/estimation/stereo_measurement_model.hpp"
#include "core/sim/diff_drive.hpp"

namespace irgs {
namespace {

// SimRandom purpose of the runner's echo stream (distinct from the simulator's 1..6).
constexpr std::uint64_t kEchoStream = 0x5E0E;
// More J+ periods than this between two samples (10 s at 1 ms) are predicted as this many.
constexpr int kMaxCasterPeriods = 10000;

void require(bool ok, const std::string& what) {
  if (!ok)
    throw std::invalid_argument("EstimatorRunner: " + what);
}

bool finitePose(const Pose2& p) {
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.theta);
}

LocCov initialCovariance(const EstimatorRunnerConfig& c) {
  LocCov p = LocCov::Zero();
  const double sp = c.initial_position_stddev_m, sh = c.initial_heading_stddev_rad;
  p.diagonal() << sp * sp, sp * sp, sh * sh;
  return p;
}

EncoderGyroFilterConfig filterConfig(const EstimatorRunnerConfig& c, double wheelbase_m) {
  EncoderGyroFilterConfig f = c.encoder_gyro;
  f.wheelbase_m = wheelbase_m;
  return f;
}

}  // namespace

const char* toString(EstimatorKind kind) {
  switch (kind) {
    case EstimatorKind::kDeadReckoning:
      return "dr";
    case EstimatorKind::kStereoEkf:
      return "ekf";
    case EstimatorKind::kEncoderGyro:
      return "encoder-gyro";
    case EstimatorKind::kMouseOdometry:
      return "mouse";
    case EstimatorKind::kStereoEkfCaster:
      return "ekf-caster";
  }
  return "?";
}

std::optional<EstimatorKind> parseEstimatorKind(std::string_view name) {
  for (EstimatorKind k : kAllEstimatorKinds)
    if (name == toString(k))
      return k;
  return std::nullopt;
}

const char* displayName(EstimatorKind kind) {
  switch (kind) {
    case EstimatorKind::kDeadReckoning:
      return "Dead reckoning (encoders)";
    case EstimatorKind::kStereoEkf:
      return "Stereo-sonar EKF (000)";
    case EstimatorKind::kEncoderGyro:
      return "Encoder + gyro filter (001)";
    case EstimatorKind::kMouseOdometry:
      return "Optical-mouse odometry (004)";
    case EstimatorKind::kStereoEkfCaster:
      return "Stereo-sonar EKF, three-caster J+ (000)";
  }
  return "?";
}

bool usesStereo(EstimatorKind kind) {
  return kind == EstimatorKind::kStereoEkf || kind == EstimatorKind::kStereoEkfCaster;
}

std::vector<StereoSensor> defaultStereoSensors() {
  // Right, left and front, as in the 000 corridor runs (tests/core/estimation).
  return {{{0.0, -0.2, -kPi / 2}, 0.2}, {{0.0, 0.2, kPi / 2}, 0.2}, {{0.25, 0.0, 0.0}, 0.2}};
}

GyroCalibration idealGyroCalibration(const GyroErrorModel& model) {
  GyroCalibration c;
  c.bias.c0_dps = model.bias_c0_dps;
  c.bias.c1_dps_per_c = model.bias_c1_dps_per_c;
  c.bias.c2_dps_per_c2 = model.bias_c2_dps_per_c2;
  c.scale.a1 = model.sf_a1;
  c.scale.a2_per_dps = model.sf_a2_per_dps;
  c.scale.a3_per_dps2 = model.sf_a3_per_dps2;
  return c;
}

void validate(const EstimatorRunnerConfig& c) {
  require(std::isfinite(c.initial_position_stddev_m) && c.initial_position_stddev_m > 0.0 &&
              std::isfinite(c.initial_heading_stddev_rad) && c.initial_heading_stddev_rad > 0.0,
          "initial stddevs must be finite and > 0");
  require(std::isfinite(c.process.wheel_variance_per_m) && c.process.wheel_variance_per_m >= 0.0 &&
              c.process.per_step.allFinite(),
          "process noise must be finite and >= 0");
  require(std::isfinite(c.stereo_period_s) && c.stereo_period_s > 0.0,
          "stereo_period_s must be finite and > 0");
  require(std::isfinite(c.max_step_travel_m) && c.max_step_travel_m > 0.0,
          "max_step_travel_m must be finite and > 0");
  require(!c.sensors.empty() || !usesStereo(c.kind), "the stereo EKF needs at least one sensor");
  require(std::isfinite(c.caster_lambda) && c.caster_lambda >= 0.0,
          "caster_lambda must be finite and >= 0");
  require(std::isfinite(c.caster_period_s) && c.caster_period_s > 0.0,
          "caster_period_s must be finite and > 0");
  if (c.caster_geometry)
    validate(*c.caster_geometry);
  for (const StereoSensor& s : c.sensors)
    require(std::isfinite(s.mount.x_m) && std::isfinite(s.mount.y_m) &&
                std::isfinite(s.mount.phi_rad) && std::isfinite(s.half_baseline_m) &&
                s.half_baseline_m > 0.0,
            "sensor mounts must be finite with a half baseline > 0");
  validate(c.ekf);
  validate(c.sonar);
}

EstimatorRunner::EstimatorRunner(const WorldMap& map, const RobotProfile& profile,
                                 const Pose2& initial_estimate, EstimatorRunnerConfig config)
    : config_((validate(config), std::move(config))),
      loc_map_(buildLocalizationMap(map)),
      echoes_(map, config_.sonar, config_.echo_noise),
      metres_per_tick_(profile.drive.metresPerTick()),
      wheelbase_m_(profile.drive.wheelbase_m),
      ekf_(LocState::Zero(), initialCovariance(config_), config_.ekf),
      caster_ticks_per_rad_(profile.drive.ticksPerWheelRad()),
      caster_dr_(LocState::Zero(), initialCovariance(config_), config_.ekf),
      echo_rng_(SimRandom::stream(config_.seed, kEchoStream)) {
  require(std::isfinite(metres_per_tick_) && metres_per_tick_ > 0.0,
          "the profile's metres per tick must be finite and > 0");
  require(std::isfinite(wheelbase_m_) && wheelbase_m_ > 0.0,
          "the profile's wheelbase must be finite and > 0");
  // The sonar's half baseline is the sensors' (one model of sensor): keep them consistent.
  for (StereoSensor& s : config_.sensors)
    s.half_baseline_m = config_.sonar.half_baseline_m;
  if (config_.kind == EstimatorKind::kEncoderGyro)
    validate(filterConfig(config_, wheelbase_m_));
  if (config_.kind == EstimatorKind::kMouseOdometry) {
    if (!config_.mouse_rig) {
      MouseRigResult rig = mouseRigFromProfile(profile);
      require(rig.rig.has_value(),
              "optical-mouse odometry needs a profile with two floor sensors (" +
                  (rig.diagnostics.empty()
                       ? std::string("no rig")
                       : rig.diagnostics.front().field + ": " + rig.diagnostics.front().message) +
                  ")");
      config_.mouse_rig = rig.rig;
    }
    validate(*config_.mouse_rig);
  }
  const bool caster_robot = profile.drive.type == DriveType::kThreeCaster;
  if (config_.kind == EstimatorKind::kStereoEkfCaster) {
    if (!config_.caster_geometry) {
      const CasterGeometryResult g = casterGeometryFromProfile(profile);
      require(g.geometry.has_value(),
              "the three-caster EKF needs a profile with drive type \"three_caster\" (" +
                  (g.diagnostics.empty()
                       ? std::string("no geometry")
                       : g.diagnostics.front().field + ": " + g.diagnostics.front().message) +
                  "), e.g. resources/robots/caster3_000.json");
      config_.caster_geometry = g.geometry;
    }
    require(std::isfinite(caster_ticks_per_rad_) && caster_ticks_per_rad_ > 0.0,
            "the profile's encoder counts per radian must be finite and > 0");
  } else if (caster_robot && config_.kind != EstimatorKind::kMouseOdometry) {
    require(false, std::string("'") + toString(config_.kind) +
                       "' needs left/right wheel encoders; this is a three-caster robot (drive "
                       "type \"three_caster\"): use 'ekf-caster'");
  }
  reset(initial_estimate);
}

void EstimatorRunner::reset(const Pose2& initial_estimate) {
  require(finitePose(initial_estimate), "non-finite initial pose");
  initial_ = {initial_estimate.x, initial_estimate.y, wrapAngle(initial_estimate.theta)};
  ekf_.reset(toLocState(initial_), initialCovariance(config_));
  caster_dr_.reset(toLocState(initial_), initialCovariance(config_));
  last_casters_.reset();
  caster_residual_total_ = 0.0;
  encoder_gyro_.reset();
  if (config_.kind == EstimatorKind::kEncoderGyro)
    encoder_gyro_.emplace(filterConfig(config_, wheelbase_m_), initial_);
  mouse_.reset();
  if (config_.kind == EstimatorKind::kMouseOdometry)
    mouse_.emplace(*config_.mouse_rig, initial_);
  echo_rng_ = SimRandom::stream(config_.seed, kEchoStream);
  has_baseline_ = false;
  last_mouse_.reset();
  next_echo_s_ = -std::numeric_limits<double>::infinity();  // fire at the first sample
  last_truth_.reset();
  step_ = {};
  step_.estimate = step_.dead_reckoning = initial_;
  step_.covariance = ekf_.covariance();
  step_.index = -1;
  metrics_ = {};
  sum_sq_pos_ = sum_sq_heading_ = sum_sq_dr_ = sum_nees_ = 0.0;
  nees_within_ = 0;
}

const EstimatorStep& EstimatorRunner::feed(const TelemetrySample& sample) {
  if (!std::isfinite(sample.time_s)) {
    step_.note = "sample with a non-finite time ignored";
    return step_;
  }
  const Pose2 previous_dr = step_.dead_reckoning;
  const std::int64_t index = step_.index + 1;
  step_ = {};
  step_.index = index;
  step_.time_s = sample.time_s;
  step_.dead_reckoning = previous_dr;
  if (sample.true_pose && finitePose(*sample.true_pose))
    step_.truth = sample.true_pose;

  const double d_left = static_cast<double>(sample.left_ticks - last_left_) * metres_per_tick_;
  const double d_right = static_cast<double>(sample.right_ticks - last_right_) * metres_per_tick_;
  const double dt = sample.time_s - last_time_s_;
  if (!has_baseline_) {
    step_.note = "baseline sample";
  } else if (dt < 0.0) {
    step_.note = "time went backwards: new baseline (robot replaced?)";
  } else if (std::abs(d_left) > config_.max_step_travel_m ||
             std::abs(d_right) > config_.max_step_travel_m) {
    step_.note = "encoder jump between samples: new baseline (robot replaced?)";
  } else if (isCasterKind() && sample.casters && last_casters_ &&
             casterJump(*last_casters_, *sample.casters)) {
    step_.note = "caster encoder jump between samples: new baseline (robot replaced?)";
  } else if (dt > 0.0 && config_.kind == EstimatorKind::kStereoEkfCaster) {
    step_.predicted = true;
    predictFromCasters(sample, dt);
  } else if (dt > 0.0) {
    step_.predicted = true;
    step_.dead_reckoning =
        integrateArc(previous_dr, 0.5 * (d_left + d_right), (d_right - d_left) / wheelbase_m_);
    if (encoder_gyro_) {
      std::optional<double> rate;
      if (sample.gyro && !sample.gyro->saturated) {
        rate = config_.gyro_calibration ? config_.gyro_calibration->compensateRadps(
                                              sample.gyro->rate_radps, sample.gyro->temperature_c)
                                        : sample.gyro->rate_radps;
        ++metrics_.readings;
      }
      step_.encoder_gyro = encoder_gyro_->step({d_right, d_left, rate, dt});
      if (step_.encoder_gyro->status == DrStepStatus::kUpdated)
        ++metrics_.accepted;
    } else if (mouse_) {
      predictFromMice(sample);
    } else if (ekf_.predictDiffDrive(d_left, d_right, wheelbase_m_, config_.process) !=
               PredictStatus::kApplied) {
      step_.note = "prediction rejected (non-finite increment)";
    }
  }
  has_baseline_ = true;
  if (sample.mouse)
    last_mouse_ = sample.mouse;
  if (sample.casters)
    last_casters_ = sample.casters;
  last_left_ = sample.left_ticks;
  last_right_ = sample.right_ticks;
  last_time_s_ = sample.time_s;

  if (usesStereo(config_.kind) && step_.truth && sample.time_s + 1e-9 >= next_echo_s_) {
    fireStereo(*step_.truth);
    // A late sample (paused, or coarser than the period) does not trigger a burst of catch-up
    // readings: the next firing is one period after this one.
    next_echo_s_ = std::max(next_echo_s_ + config_.stereo_period_s,
                            sample.time_s + 0.5 * config_.stereo_period_s);
  }
  finishStep(sample);
  return step_;
}

void EstimatorRunner::predictFromMice(const TelemetrySample& sample) {
  if (!sample.mouse) {
    step_.note = "no floor-sensor reading: the estimate holds";
    return;
  }
  ++metrics_.readings;
  // The sample carries cumulative counts: this interval's report is the difference.
  const auto since = [](const MouseCounts& now, const MouseCounts& before) {
    return MouseCounts{now.dx - before.dx, now.dy - before.dy, now.status};
  };
  const MouseReading before = last_mouse_.value_or(*sample.mouse);
  step_.mouse_motion = mouse_->update(since(sample.mouse->right, before.right),
                                      since(sample.mouse->left, before.left));
  const TwoSensorMotion& motion = *step_.mouse_motion;
  if (motion.status == MouseMotionStatus::kOk)
    ++metrics_.accepted;
  else
    step_.note = std::string("floor sensors: ") + toString(motion.status);
  // Paper 004 gives no noise model: the covariance grows as for encoder dead reckoning over the
  // same motion (the centre's chord and rotation as equivalent wheel travels).
  const double travel = std::copysign(motion.centre.norm(), motion.centre.x());
  const double half_turn = 0.5 * motion.dtheta_rad * wheelbase_m_;
  ekf_.predictDiffDrive(travel - half_turn, travel + half_turn, wheelbase_m_, config_.process);
}

bool EstimatorRunner::casterJump(const CasterEncoders& before, const CasterEncoders& now) const {
  const double r = config_.caster_geometry ? config_.caster_geometry->wheel_radius_m : 0.0;
  for (std::size_t i = 0; i < 3; ++i) {
    const double travel =
        static_cast<double>(now.drive_ticks[i] - before.drive_ticks[i]) / caster_ticks_per_rad_;
    if (std::abs(travel * r) > config_.max_step_travel_m)
      return true;
  }
  return false;
}

void EstimatorRunner::predictFromCasters(const TelemetrySample& sample, double dt) {
  step_.dead_reckoning = caster_dr_.pose();
  if (!sample.casters) {
    step_.note = "no caster encoders: the estimate holds";
    return;
  }
  const CasterEncoders before = last_casters_.value_or(*sample.casters);
  const int periods = static_cast<int>(std::clamp(std::ceil(dt / config_.caster_period_s - 1e-9),
                                                  1.0, static_cast<double>(kMaxCasterPeriods)));
  // The robot's own mean residual per period over the interval, when it reports one: the
  // re-split counts below have constant rates, so their residual misses the slip and
  // quantisation of the robot's individual periods.
  std::optional<double> robot_residual;
  if (config_.caster_robot_residual && last_casters_) {
    const std::int64_t n = sample.casters->residual_periods - before.residual_periods;
    const double sum = sample.casters->residual_sum_rad - before.residual_sum_rad;
    if (n > 0 && std::isfinite(sum) && sum >= 0.0)
      robot_residual = sum / static_cast<double>(n);
  }
  step_.caster_residual_from_robot = robot_residual.has_value();
  int singular = 0;
  for (int k = 0; k < periods; ++k) {
    CasterOdometry odo = casterIntervalOdometry(*config_.caster_geometry, before, *sample.casters,
                                                caster_ticks_per_rad_, k, periods);
    if (robot_residual)
      odo.residual_norm = *robot_residual;  // (36) Q = lambda ||e|| with the robot's ||e||
    const CasterPrediction p = ekf_.predictCaster(odo, config_.caster_lambda);
    if (p.status != PredictStatus::kApplied) {
      ++singular;
      continue;
    }
    caster_dr_.predictCaster(odo, config_.caster_lambda);
    ++step_.caster_periods;
    step_.caster_residual_sum += p.residual_norm;
  }
  if (singular > 0)
    step_.note = "caster steering makes J+ singular: " + std::to_string(singular) + " of " +
                 std::to_string(periods) + " periods skipped";
  metrics_.caster_periods += step_.caster_periods;
  caster_residual_total_ += step_.caster_residual_sum;
  if (metrics_.caster_periods > 0)
    metrics_.mean_caster_residual_rad =
        caster_residual_total_ / static_cast<double>(metrics_.caster_periods);
  step_.dead_reckoning = caster_dr_.pose();
}

void EstimatorRunner::fireStereo(const Pose2& truth) {
  for (std::size_t i = 0; i < config_.sensors.size(); ++i) {
    const StereoSensor& sensor = config_.sensors[i];
    const SimulatedEcho echo =
        echoes_.echo(sensorWorldPose(toLocState(truth), sensor.mount), echo_rng_);
    StereoReadingRecord record;
    record.sensor = i;
    record.echo = echo.status;
    if (echo.status != EchoStatus::kNoReflector)
      record.true_reflector_id = echo.reflector_id;
    if (echo.status == EchoStatus::kEcho) {
      ++metrics_.readings;
      record.update = ekf_.update(echo.paths, sensor, loc_map_);
      record.accepted = record.update.status == UpdateStatus::kUpdated;
      if (record.accepted)
        ++metrics_.accepted;
    }
    step_.readings.push_back(std::move(record));
  }
}

void EstimatorRunner::currentEstimate() {
  if (encoder_gyro_) {
    step_.estimate = encoder_gyro_->pose();
    // The error states after feedback: (dx, dy, dpsi) is the pose error covariance.
    step_.covariance = encoder_gyro_->covariance().block<3, 3>(kDrDx, kDrDx);
  } else if (mouse_) {
    step_.estimate = mouse_->pose();
    step_.covariance = ekf_.covariance();
  } else {
    step_.estimate = ekf_.pose();
    step_.covariance = ekf_.covariance();
  }
}

void EstimatorRunner::finishStep(const TelemetrySample& sample) {
  currentEstimate();
  if (!step_.truth)
    return;
  const Pose2& truth = *step_.truth;
  LocState e = toLocState(step_.estimate) - toLocState(truth);
  e(kLocPhi) = wrapAngle(e(kLocPhi));
  step_.error = e;
  const Eigen::LLT<LocCov> llt(step_.covariance);
  if (llt.info() == Eigen::Success && step_.covariance.allFinite()) {
    const double nees = e.dot(llt.solve(e));
    if (std::isfinite(nees)) {
      step_.nees = nees;
      sum_nees_ += nees;
      ++metrics_.nees_steps;
      if (nees <= kChi2Dof3P95)
        ++nees_within_;
    }
  }
  const double pos = e.head<2>().norm();
  const double heading = std::abs(e(kLocPhi));
  const double dr_pos = (step_.dead_reckoning.position() - truth.position()).norm();
  if (metrics_.steps == 0)
    first_truth_time_s_ = sample.time_s;
  metrics_.duration_s = sample.time_s - first_truth_time_s_;
  if (last_truth_)
    metrics_.distance_m += (truth.position() - last_truth_->position()).norm();
  last_truth_ = truth;
  ++metrics_.steps;
  sum_sq_pos_ += pos * pos;
  sum_sq_heading_ += heading * heading;
  sum_sq_dr_ += dr_pos * dr_pos;
  const double n = static_cast<double>(metrics_.steps);
  metrics_.rms_position_error_m = std::sqrt(sum_sq_pos_ / n);
  metrics_.rms_heading_error_rad = std::sqrt(sum_sq_heading_ / n);
  metrics_.dr_rms_position_error_m = std::sqrt(sum_sq_dr_ / n);
  metrics_.max_position_error_m = std::max(metrics_.max_position_error_m, pos);
  metrics_.final_position_error_m = pos;
  metrics_.final_heading_error_rad = heading;
  metrics_.dr_final_position_error_m = dr_pos;
  metrics_.dr_final_heading_error_rad =
      std::abs(wrapAngle(step_.dead_reckoning.theta - truth.theta));
  if (metrics_.nees_steps > 0) {
    metrics_.mean_nees = sum_nees_ / static_cast<double>(metrics_.nees_steps);
    metrics_.nees_within_95 =
        static_cast<double>(nees_within_) / static_cast<double>(metrics_.nees_steps);
  }
}

}  // namespace irgs
