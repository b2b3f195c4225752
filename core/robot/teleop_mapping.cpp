#include "core/robot/teleop_mapping.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace irgs {

void validate(const TeleopMappingConfig& c) {
  const auto axis_ok = [](const TeleopAxisConfig& a) {
    return a.axis >= 0 && a.axis < GamepadState::kAxes;
  };
  if (!(c.deadband >= 0.0 && c.deadband < 1.0))
    throw std::invalid_argument("teleop mapping: deadband must be in [0, 1)");
  if (!(c.expo >= 0.0 && c.expo <= 1.0))
    throw std::invalid_argument("teleop mapping: expo must be in [0, 1]");
  if (!(c.normal_fraction > 0.0 && c.normal_fraction <= 1.0))
    throw std::invalid_argument("teleop mapping: normal speed fraction must be in (0, 1]");
  if (!axis_ok(c.linear) || !axis_ok(c.angular))
    throw std::invalid_argument("teleop mapping: axis index out of range");
}

double shapeAxis(double value, double deadband, double expo) {
  if (!std::isfinite(value))
    return 0.0;
  const double v = std::clamp(value, -1.0, 1.0);
  const double magnitude = std::abs(v);
  if (magnitude <= deadband)
    return 0.0;
  // Rescaled so the output starts at 0 at the deadband's edge (no jump) and reaches 1 at full.
  const double r = (magnitude - deadband) / (1.0 - deadband);
  const double shaped = (1.0 - expo) * r + expo * r * r * r;
  return std::copysign(std::clamp(shaped, 0.0, 1.0), v);
}

namespace {

double finiteOrZero(double v) {
  return std::isfinite(v) && v > 0.0 ? v : 0.0;
}

}  // namespace

VelocityCommand mapStick(double x, double y, double deadband, double expo, double max_linear_mps,
                         double max_angular_radps) {
  VelocityCommand c;
  c.linear_mps = -shapeAxis(y, deadband, expo) * finiteOrZero(max_linear_mps);
  c.angular_radps = -shapeAxis(x, deadband, expo) * finiteOrZero(max_angular_radps);
  return c;
}

VelocityCommand mapGamepad(const GamepadState& state, const TeleopMappingConfig& config,
                           const MotionLimits& limits) {
  if (config.deadman_button >= 0 && !state.pressed(config.deadman_button))
    return {};
  const double fraction = state.pressed(config.turbo_button) ? 1.0 : config.normal_fraction;
  const auto axis = [&](const TeleopAxisConfig& a) {
    const double raw = state.axes[static_cast<std::size_t>(a.axis)];
    return shapeAxis(a.invert ? -raw : raw, config.deadband, config.expo);
  };
  VelocityCommand c;
  c.linear_mps = axis(config.linear) * fraction * finiteOrZero(limits.max_speed_mps);
  c.angular_radps = axis(config.angular) * fraction * finiteOrZero(limits.max_turn_rate_radps);
  return c;
}

}  // namespace irgs
