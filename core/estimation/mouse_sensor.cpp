#include "core/estimation/mouse_sensor.hpp"

#include <cmath>
#include <stdexcept>

namespace irgs {

namespace {

// sin(x)/x with the series near 0 (full precision for tiny turns, no 0/0).
double sinc(double x) {
  return std::abs(x) < 1e-4 ? 1.0 - x * x / 6.0 : std::sin(x) / x;
}

Vec2 rotate(const Vec2& v, double angle_rad) {
  const double c = std::cos(angle_rad), s = std::sin(angle_rad);
  return {c * v.x() - s * v.y(), s * v.x() + c * v.y()};
}

bool finitePositive(double v) {
  return std::isfinite(v) && v > 0.0;
}

}  // namespace

void validate(const MouseSensorSpec& spec) {
  if (!finitePositive(spec.counts_per_inch) || !finitePositive(spec.max_speed_mps) ||
      !finitePositive(spec.max_lift_m) || !finitePositive(spec.frame_rate_hz))
    throw std::invalid_argument(
        "MouseSensorSpec: counts_per_inch, max_speed_mps, max_lift_m and frame_rate_hz must be "
        "finite and > 0");
}

void validate(const MouseNoise& noise) {
  if (!std::isfinite(noise.scale_error) || !(noise.scale_error > -1.0))
    throw std::invalid_argument("MouseNoise: scale_error must be finite and > -1");
  if (!std::isfinite(noise.relative_stddev) || !(noise.relative_stddev >= 0.0) ||
      !std::isfinite(noise.stddev_m) || !(noise.stddev_m >= 0.0))
    throw std::invalid_argument("MouseNoise: stddevs must be finite and >= 0");
}

const char* toString(MouseStatus status) {
  switch (status) {
    case MouseStatus::kTracking:
      return "tracking";
    case MouseStatus::kSaturated:
      return "saturated";
    case MouseStatus::kLifted:
      return "lifted";
  }
  return "unknown";
}

SensorMotion sensorMotion(double x_bar_m, double y_bar_m) {
  // (1)-(3) with atan2/hypot (A004-5): no special cases for alpha = 0 or pi.
  return {std::atan2(y_bar_m, x_bar_m), std::hypot(x_bar_m, y_bar_m)};
}

Pose2 applyIncrement(const Pose2& start, const BodyIncrement& increment) {
  // Constant twist: the chord is sinc(dθ/2) R(dθ/2) (dx, dy) in the start body frame.
  const double half = 0.5 * increment.dtheta_rad;
  const Vec2 chord = sinc(half) * rotate({increment.dx_m, increment.dy_m}, half);
  const Vec2 p = start.toWorld(chord);
  return {p.x(), p.y(), wrapAngle(start.theta + increment.dtheta_rad)};
}

BodyIncrement incrementBetween(const Pose2& from, const Pose2& to) {
  const double dtheta = wrapAngle(to.theta - from.theta);
  const double half = 0.5 * dtheta;
  const Vec2 chord = from.toBody(to.position());
  const Vec2 linear = rotate(chord, -half) / sinc(half);
  return {linear.x(), linear.y(), dtheta};
}

Vec2 sensorDisplacement(const MouseMount& mount, const BodyIncrement& increment) {
  // Velocity of a body-fixed point p in the body frame: v + omega x p = (vx - w py, vy + w px).
  const Vec2 body(increment.dx_m - increment.dtheta_rad * mount.y_m,
                  increment.dy_m + increment.dtheta_rad * mount.x_m);
  return rotate(body, -mount.phi_rad);
}

MouseSensorSimulator::MouseSensorSimulator(MouseSensorSpec spec, MouseMount mount, MouseNoise noise)
    : spec_(spec), mount_(mount), noise_(noise) {
  validate(spec_);
  validate(noise_);
  if (!std::isfinite(mount_.x_m) || !std::isfinite(mount_.y_m) || !std::isfinite(mount_.phi_rad))
    throw std::invalid_argument("MouseSensorSimulator: non-finite mount");
}

MouseCounts MouseSensorSimulator::sample(const BodyIncrement& increment, double dt_s,
                                         double floor_gap_m, SimRandom& rng) {
  if (!std::isfinite(increment.dx_m) || !std::isfinite(increment.dy_m) ||
      !std::isfinite(increment.dtheta_rad) || !std::isfinite(floor_gap_m) || !finitePositive(dt_s))
    throw std::invalid_argument("MouseSensorSimulator::sample: non-finite input or dt_s <= 0");
  // Draw first, whatever happens, so the stream does not depend on the motion.
  const double n1 = rng.gaussian();
  const double n2 = rng.gaussian();

  MouseCounts out;
  if (floor_gap_m > spec_.max_lift_m) {
    // The sensor loses the floor image: nothing is reported and the chip's partial count is lost.
    remainder_counts_.setZero();
    out.status = MouseStatus::kLifted;
    return out;
  }
  Vec2 motion = sensorDisplacement(mount_, increment);
  const double length = motion.norm();
  motion *= 1.0 + noise_.scale_error;
  motion.x() += n1 * (noise_.relative_stddev * length + noise_.stddev_m);
  motion.y() += n2 * (noise_.relative_stddev * length + noise_.stddev_m);
  const double limit = spec_.max_speed_mps * dt_s;
  if (length > limit) {
    motion *= limit / length;  // [A] clipped along the true direction
    out.status = MouseStatus::kSaturated;
  }
  // Quantise, carrying the remainder (the chip accumulates sub-count motion).
  const Vec2 total = remainder_counts_ + motion / spec_.metresPerCount();
  if (!(total.cwiseAbs().maxCoeff() < 1e15))  // llround would overflow: not a sampling interval
    throw std::invalid_argument("MouseSensorSimulator::sample: displacement out of range");
  out.dx = std::llround(total.x());
  out.dy = std::llround(total.y());
  remainder_counts_ = total - Vec2(static_cast<double>(out.dx), static_cast<double>(out.dy));
  return out;
}

}  // namespace irgs
