#include "core/sim/caster_drive_sim.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "core/estimation/mouse_sensor.hpp"

namespace irgs {

namespace {

void addError(std::vector<Diagnostic>& out, const std::string& field, const std::string& message) {
  out.push_back({Severity::kError, "", 0, 0, field, message});
}

bool finiteNonNegative(const nlohmann::json& v) {
  return v.is_number() && std::isfinite(v.get<double>()) && v.get<double>() >= 0.0;
}

std::int64_t counts(double rad, double ticks_per_rad) {
  return static_cast<std::int64_t>(std::floor(rad * ticks_per_rad));
}

}  // namespace

void validate(const CasterErrorModel& e) {
  for (double s : e.radius_scale) {
    if (!std::isfinite(s) || !(s > 0.0))
      throw std::invalid_argument("CasterErrorModel: radius_scale must be finite and > 0");
  }
  if (!std::isfinite(e.drive_slip_stddev) || !(e.drive_slip_stddev >= 0.0) ||
      !std::isfinite(e.steering_backlash_stddev_rad) || !(e.steering_backlash_stddev_rad >= 0.0))
    throw std::invalid_argument("CasterErrorModel: stddevs must be finite and >= 0");
}

CasterErrorResult casterErrorsFromProfile(const RobotProfile& profile) {
  CasterErrorResult result;
  CasterErrorModel e;
  const auto caster = profile.drive.extra.find("three_caster");
  if (caster == profile.drive.extra.end() || !caster->is_object() ||
      !caster->contains("simulated_errors")) {
    result.errors = e;
    return result;
  }
  const std::string ptr = "/drive/three_caster/simulated_errors";
  const nlohmann::json& j = (*caster)["simulated_errors"];
  std::vector<Diagnostic>& out = result.diagnostics;
  if (!j.is_object()) {
    addError(out, ptr, "expected an object");
    return result;
  }
  if (const auto it = j.find("radius_scale"); it != j.end()) {
    if (!it->is_array() || it->size() != 3) {
      addError(out, ptr + "/radius_scale", "expected an array of 3 numbers");
    } else {
      for (std::size_t i = 0; i < 3; ++i) {
        const nlohmann::json& v = (*it)[i];
        if (!v.is_number() || !std::isfinite(v.get<double>()) || !(v.get<double>() > 0.0))
          addError(out, ptr + "/radius_scale/" + std::to_string(i), "must be a number > 0");
        else
          e.radius_scale[i] = v.get<double>();
      }
    }
  }
  const auto readStddev = [&](const char* key, double& into) {
    const auto it = j.find(key);
    if (it == j.end())
      return;
    if (!finiteNonNegative(*it))
      addError(out, ptr + "/" + key, "must be a finite number >= 0");
    else
      into = it->get<double>();
  };
  readStddev("drive_slip_stddev", e.drive_slip_stddev);
  readStddev("steering_backlash_stddev_rad", e.steering_backlash_stddev_rad);
  if (!hasErrors(out))
    result.errors = e;
  return result;
}

CasterDriveSimulator::CasterDriveSimulator(const CasterDriveGeometry& nominal,
                                           const CasterErrorModel& errors, double ticks_per_rad,
                                           double period_s)
    : nominal_(nominal), errors_(errors), ticks_per_rad_(ticks_per_rad), period_s_(period_s) {
  irgs::validate(nominal_);
  irgs::validate(errors_);
  if (!std::isfinite(ticks_per_rad_) || !(ticks_per_rad_ > 0.0))
    throw std::invalid_argument("CasterDriveSimulator: ticks per radian must be > 0");
  if (!std::isfinite(period_s_) || !(period_s_ > 0.0))
    throw std::invalid_argument("CasterDriveSimulator: period must be > 0");
}

void CasterDriveSimulator::advance(const BodyTwist& twist, double dt_s, Pose2& odometry,
                                   SimRandom& rng) {
  if (!(dt_s > 0.0) || !twist.allFinite())
    return;
  const int n = std::max(1, static_cast<int>(std::ceil(dt_s / period_s_ - 1e-9)));
  const double h = dt_s / static_cast<double>(n);
  for (int k = 0; k < n; ++k)
    period(twist, h, odometry, rng);
}

void CasterDriveSimulator::period(const BodyTwist& twist, double h, Pose2& odometry,
                                  SimRandom& rng) {
  // True increments from (26) at the steering of the period's start (the harness of 000's
  // corridor run did the same at 1 ms).
  const CasterVector delta = casterJacobian(nominal_, steering_) * twist * h;
  const CasterEncoders before = encoders_;
  for (std::size_t i = 0; i < 3; ++i) {
    const auto row = static_cast<Eigen::Index>(2 * i);
    // A larger true wheel turns less for the same path.
    const double drive = delta(row) / errors_.radius_scale[i];
    const double steer = delta(row + 1);
    steering_[i] = wrapAngle(steering_[i] + steer);
    double slip = 1.0;
    if (errors_.drive_slip_stddev > 0.0)
      slip += errors_.drive_slip_stddev * rng.gaussian();
    double backlash = 0.0;
    if (errors_.steering_backlash_stddev_rad > 0.0)
      backlash = errors_.steering_backlash_stddev_rad * rng.gaussian();
    drive_counted_[i] += drive * slip;
    // The steering reading is the true angle off by the backlash: it does not accumulate.
    steering_unwrapped_[i] += steer;
    steering_counted_[i] = steering_unwrapped_[i] + backlash;
    encoders_.drive_ticks[i] = counts(drive_counted_[i], ticks_per_rad_);
    encoders_.steering_ticks[i] = counts(steering_counted_[i], ticks_per_rad_);
  }
  // The robot's own dead reckoning: J+ on this period's count differences.
  const CasterOdometry odo = casterIntervalOdometry(nominal_, before, encoders_, ticks_per_rad_);
  if (odo.ok) {
    odometry = applyIncrement(odometry, {odo.body_delta(0), odo.body_delta(1), odo.body_delta(2)});
    // What the robot reports of its own J+ (CasterEncoders): the residual of this period.
    encoders_.residual_sum_rad += odo.residual_norm;
    ++encoders_.residual_periods;
  }
}

}  // namespace irgs
