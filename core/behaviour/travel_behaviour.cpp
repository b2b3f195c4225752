#include "core/behaviour/travel_behaviour.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <utility>

namespace irgs {
namespace {

// Fraction of the ideal braking speed commanded, so latency of one sample and the acceleration
// limit of the robot cannot make it overshoot.
constexpr double kBrakeMargin = 0.7;
// Progress the watchdog needs to see: heading error (rad) while turning, distance while driving.
constexpr double kTurnProgress_rad = degToRad(0.5);
constexpr double kDriveProgress_m = 0.01;
// Closer than this to the turning point, the heading hold keeps the leg direction instead of
// aiming at the point (whose bearing swings as the robot passes it).
constexpr double kAimMinDistance_m = 0.05;
// Margin beyond the body's front extent for the sonar stop.
constexpr double kStopMargin_m = 0.02;
// Sonar readings used by the safety stop: range limit of the view, m.
constexpr double kSonarViewRange_m = 4.0;

std::string formatPoint(const Vec2& p) {
  std::array<char, 64> buffer{};
  std::snprintf(buffer.data(), buffer.size(), "(%.2f, %.2f)", p.x(), p.y());
  return buffer.data();
}

std::string formatMetres(double d) {
  std::array<char, 32> buffer{};
  std::snprintf(buffer.data(), buffer.size(), "%.2f m", d);
  return buffer.data();
}

bool finitePose(const Pose2& p) {
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.theta);
}

// Speed that still allows stopping within `distance` at deceleration `accel`, scaled down by the
// brake margin, clamped to [min_speed, max_speed].
double approachSpeed(double distance, double accel, double min_speed, double max_speed,
                     double gain) {
  const double brake = std::sqrt(2.0 * accel * std::max(distance, 0.0)) * kBrakeMargin;
  return std::clamp(std::min(brake, gain * distance), min_speed, max_speed);
}

TravelOptions fromConfig(const RobotProfile& profile, const TravelConfig& config) {
  if (!(config.speed_mps > 0.0) || !(config.turn_rate_radps > 0.0) ||
      !(config.stop_distance_m >= 0.0) || !std::isfinite(config.speed_mps) ||
      !std::isfinite(config.turn_rate_radps) || !std::isfinite(config.stop_distance_m))
    throw std::invalid_argument("TravelConfig: speeds must be > 0 and the stop distance >= 0");
  TravelOptions options = travelOptionsFor(profile);
  options.max_speed_mps = config.speed_mps;
  options.min_speed_mps = std::min(options.min_speed_mps, config.speed_mps);
  options.max_turn_rate_radps = config.turn_rate_radps;
  options.min_turn_rate_radps = std::min(options.min_turn_rate_radps, config.turn_rate_radps);
  options.stop_distance_m = config.stop_distance_m;
  return options;
}

}  // namespace

std::string_view toString(TravelBehaviour::Phase phase) {
  switch (phase) {
    case TravelBehaviour::Phase::kTurn:
      return "turn";
    case TravelBehaviour::Phase::kDrive:
      return "drive";
    case TravelBehaviour::Phase::kDone:
      return "done";
  }
  return "unknown";
}

TravelOptions travelOptionsFor(const RobotProfile& profile) {
  TravelOptions options;
  const MotionLimits& limits = profile.limits;
  if (std::isfinite(limits.max_speed_mps) && limits.max_speed_mps > options.min_speed_mps)
    options.max_speed_mps = std::min(options.max_speed_mps, limits.max_speed_mps);
  if (std::isfinite(limits.max_accel_mps2) && limits.max_accel_mps2 > 0.0)
    options.accel_mps2 = limits.max_accel_mps2;
  if (std::isfinite(limits.max_turn_rate_radps) &&
      limits.max_turn_rate_radps > options.min_turn_rate_radps)
    options.max_turn_rate_radps = std::min(options.max_turn_rate_radps, limits.max_turn_rate_radps);
  if (std::isfinite(limits.max_turn_accel_radps2) && limits.max_turn_accel_radps2 > 0.0)
    options.turn_accel_radps2 = limits.max_turn_accel_radps2;
  return options;
}

std::optional<std::string> travelOptionsError(const TravelOptions& o) {
  const std::array<std::pair<const char*, double>, 11> positive{{
      {"max_speed_mps", o.max_speed_mps},
      {"min_speed_mps", o.min_speed_mps},
      {"accel_mps2", o.accel_mps2},
      {"max_turn_rate_radps", o.max_turn_rate_radps},
      {"min_turn_rate_radps", o.min_turn_rate_radps},
      {"turn_accel_radps2", o.turn_accel_radps2},
      {"turn_gain", o.turn_gain},
      {"heading_gain", o.heading_gain},
      {"heading_tolerance_rad", o.heading_tolerance_rad},
      {"arrival_tolerance_m", o.arrival_tolerance_m},
      {"stall_timeout_s", o.stall_timeout_s},
  }};
  for (const auto& [field, value] : positive) {
    if (!std::isfinite(value) || value <= 0.0)
      return std::string(field) + " must be finite and positive";
  }
  if (!std::isfinite(o.stop_distance_m) || o.stop_distance_m < 0.0)
    return "stop_distance_m must be finite and non-negative";
  if (o.min_speed_mps > o.max_speed_mps)
    return "min_speed_mps exceeds max_speed_mps";
  if (o.min_turn_rate_radps > o.max_turn_rate_radps)
    return "min_turn_rate_radps exceeds max_turn_rate_radps";
  return std::nullopt;
}

TravelBehaviour::TravelBehaviour(TravelPlan plan, TravelOptions options)
    : plan_(std::move(plan)), options_(options) {
  validate();
}

TravelBehaviour::TravelBehaviour(const RobotProfile& profile, TravelPlan plan,
                                 const TravelOptions& options)
    : plan_(std::move(plan)), options_(options) {
  validate();
  if (options_.stop_distance_m > 0.0) {
    sonar_.emplace(profile, kSonarViewRange_m);
    for (const Vec2& v : profile.body_outline)
      front_extent_m_ = std::max(front_extent_m_, v.x());
  }
}

TravelBehaviour::TravelBehaviour(const RobotProfile& profile, TravelPlan plan, TravelConfig config)
    : TravelBehaviour(profile, std::move(plan), fromConfig(profile, config)) {}

void TravelBehaviour::validate() {
  if (const auto error = travelOptionsError(options_))
    throw std::invalid_argument("TravelBehaviour: " + *error);
  for (const TravelSegment& s : plan_.segments) {
    if (!std::isfinite(s.from.x()) || !std::isfinite(s.from.y()) || !std::isfinite(s.to.x()) ||
        !std::isfinite(s.to.y()) || !std::isfinite(s.heading_rad) || !std::isfinite(s.distance_m))
      throw std::invalid_argument("TravelBehaviour: plan with non-finite values");
  }
  if (plan_.segments.empty())
    finish(false, "nothing to travel");
  else
    phase_text_ = "turn 1/" + std::to_string(plan_.segments.size());
}

void TravelBehaviour::finish(bool failed, std::string message) {
  phase_ = Phase::kDone;
  segment_ = plan_.segments.size();
  failed_ = failed;
  message_ = std::move(message);
  phase_text_ = failed ? "failed" : "arrived";
}

void TravelBehaviour::startSegment(std::size_t index, double time_s) {
  segment_ = index;
  leg_progress_m_ = 0.0;
  best_measure_.reset();
  improved_at_s_ = time_s;
  if (segment_ >= plan_.segments.size()) {
    const Vec2 goal = plan_.segments.empty() ? Vec2::Zero() : plan_.segments.back().to;
    finish(false, "arrived at the goal " + formatPoint(goal));
    return;
  }
  phase_ = Phase::kTurn;
  phase_text_ =
      "turn " + std::to_string(segment_ + 1) + "/" + std::to_string(plan_.segments.size());
}

void TravelBehaviour::noteProgress(double measure, double time_s) {
  // measure shrinks with progress (heading error or remaining distance).
  const double step = phase_ == Phase::kTurn ? kTurnProgress_rad : kDriveProgress_m;
  if (!best_measure_ || measure < *best_measure_ - step) {
    best_measure_ = measure;
    improved_at_s_ = time_s;
  }
}

bool TravelBehaviour::stalled(double time_s) const {
  return time_s - improved_at_s_ > options_.stall_timeout_s;
}

VelocityCommand TravelBehaviour::onSample(const TelemetrySample& sample) {
  if (phase_ == Phase::kDone)
    return {};
  // A sample without a usable pose gives no new information: stop until a good one arrives.
  if (!finitePose(sample.odometry_pose) || !std::isfinite(sample.time_s))
    return {};
  if (sonar_)
    sonar_->update(sample);
  if (!started_) {
    started_ = true;
    startSegment(0, sample.time_s);
  }
  for (int guard = 0; guard < 3 && phase_ != Phase::kDone; ++guard) {
    const Phase before = phase_;
    const std::size_t segment_before = segment_;
    const VelocityCommand command = phase_ == Phase::kTurn
                                        ? turnCommand(sample.odometry_pose, sample.time_s)
                                        : driveCommand(sample);
    // A phase that ended on this sample hands over at once (e.g. a zero turn).
    if (phase_ == before && segment_ == segment_before)
      return command;
    // After a turn the sonars look elsewhere: their older readings no longer apply.
    if (sonar_ && before == Phase::kTurn)
      sonar_->forgetBefore(sample.time_s);
  }
  return {};
}

VelocityCommand TravelBehaviour::turnCommand(const Pose2& pose, double time_s) {
  const TravelSegment& s = plan_.segments[segment_];
  const double error = wrapAngle(s.heading_rad - pose.theta);
  if (std::abs(error) <= options_.heading_tolerance_rad) {
    phase_ = Phase::kDrive;
    phase_text_ =
        "drive " + std::to_string(segment_ + 1) + "/" + std::to_string(plan_.segments.size());
    best_measure_.reset();
    improved_at_s_ = time_s;
    return {};
  }
  noteProgress(std::abs(error), time_s);
  if (stalled(time_s)) {
    finish(true, "turn " + std::to_string(segment_ + 1) + " made no progress at " +
                     formatPoint(pose.position()));
    return {};
  }
  const double rate =
      approachSpeed(std::abs(error), options_.turn_accel_radps2, options_.min_turn_rate_radps,
                    options_.max_turn_rate_radps, options_.turn_gain);
  return {0.0, std::copysign(rate, error)};
}

VelocityCommand TravelBehaviour::driveCommand(const TelemetrySample& sample) {
  const TravelSegment& s = plan_.segments[segment_];
  const Pose2& pose = sample.odometry_pose;
  const Vec2 p = pose.position();
  // The leg runs from the segment start to its turning point along the segment direction; with
  // steering off it is the quantised heading for the planned distance.
  const Vec2 heading_dir(std::cos(s.heading_rad), std::sin(s.heading_rad));
  const Vec2 leg = s.to - s.from;
  const bool steer = options_.steer_to_turning_points && leg.norm() > 1e-9;
  const Vec2 dir = steer ? Vec2(leg.normalized()) : heading_dir;
  const Vec2 target = steer ? s.to : Vec2(s.from + heading_dir * s.distance_m);
  const double remaining = (target - p).dot(dir);
  leg_progress_m_ = std::clamp(s.distance_m - remaining, 0.0, s.distance_m);

  if (remaining <= options_.arrival_tolerance_m) {
    arrivals_.push_back(s.to);
    arrival_positions_.push_back(p);
    done_distance_m_ += s.distance_m;
    const std::size_t reached = segment_ + 1;
    if (reached < plan_.segments.size()) {
      message_ = "arrived at turning point " + std::to_string(reached) + "/" +
                 std::to_string(plan_.segments.size() - 1) + " " + formatPoint(s.to);
    }
    startSegment(reached, sample.time_s);
    return {};
  }
  if (options_.stop_on_bumper && inContact(sample)) {
    finish(true, "bumper pressed at " + formatPoint(p) + " on leg " + std::to_string(segment_ + 1));
    return {};
  }
  if (sonar_) {
    const auto front = sonar_->frontDistance();
    if (front && *front < options_.stop_distance_m &&
        *front < remaining + front_extent_m_ + kStopMargin_m) {
      finish(true, "blocked " + formatMetres(*front) + " ahead at " + formatPoint(p) + " on leg " +
                       std::to_string(segment_ + 1));
      return {};
    }
  }
  noteProgress(remaining, sample.time_s);
  if (stalled(sample.time_s)) {
    finish(true, "leg " + std::to_string(segment_ + 1) + " made no progress at " + formatPoint(p));
    return {};
  }
  const Vec2 to_target = target - p;
  const double aim = to_target.norm() > kAimMinDistance_m ? std::atan2(to_target.y(), to_target.x())
                                                          : std::atan2(dir.y(), dir.x());
  const double heading_error = wrapAngle(aim - pose.theta);
  const double omega = std::clamp(options_.heading_gain * heading_error,
                                  -options_.max_turn_rate_radps, options_.max_turn_rate_radps);
  double v = approachSpeed(remaining, options_.accel_mps2, options_.min_speed_mps,
                           options_.max_speed_mps, 1e9);
  // Far off the leg direction (a disturbed robot), turn first rather than sweep sideways.
  v *= std::max(0.0, std::cos(heading_error));
  return {v, omega};
}

BehaviourStatus TravelBehaviour::status() const {
  BehaviourStatus status;
  status.phase = phase_text_;
  status.finished = phase_ == Phase::kDone;
  status.failed = failed_;
  status.message = message_;
  const double total = plan_.total_distance_m;
  if (status.finished && !failed_)
    status.progress = 1.0;
  else if (total > 1e-9)
    status.progress = std::clamp((done_distance_m_ + leg_progress_m_) / total, 0.0, 1.0);
  else if (!plan_.segments.empty())
    status.progress = static_cast<double>(segment_) / static_cast<double>(plan_.segments.size());
  return status;
}

}  // namespace irgs
