#include "app/robot/firmware_params.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace irgs::app {

const std::array<ParamSpec, static_cast<std::size_t>(ParamId::kCount)>& paramSpecs() {
  // TELEOP_TIMEOUT stays below 0.45 s so the "motors stop within 0.5 s of the last teleop
  // frame" rule holds for every allowed value (the stop itself takes one 10 ms step).
  static const std::array<ParamSpec, static_cast<std::size_t>(ParamId::kCount)> specs = {{
      {"TELEOP_TIMEOUT", 0.05, 0.45, "s", "MANUAL_CONTROL older than this no longer drives"},
      {"HB_TIMEOUT", 0.5, 10.0, "s", "no GCS HEARTBEAT for this long stops all motion"},
      {"MAX_SPEED", 0.01, 10.0, "m/s", "full-stick and behaviour speed cap"},
      {"MAX_TURN_RATE", 0.05, 20.0, "rad/s", "full-stick and behaviour turn-rate cap"},
      {"SR_POSE", 0.0, 100.0, "Hz", "LOCAL_POSITION_NED, ATTITUDE, ODOMETRY, ticks, POSE_2D"},
      {"SR_SONAR", 0.0, 100.0, "Hz", "DISTANCE_SENSOR batches, IRGS_SONAR_SCAN"},
      {"SR_CONTACT", 0.0, 100.0, "Hz", "IRGS_CONTACT (also sent on every bumper change)"},
      {"SR_IMU", 0.0, 100.0, "Hz", "SCALED_IMU"},
      {"SR_STATUS", 0.0, 10.0, "Hz", "SYS_STATUS"},
  }};
  return specs;
}

std::optional<ParamId> findParam(std::string_view name) {
  const auto& specs = paramSpecs();
  for (std::size_t i = 0; i < specs.size(); ++i) {
    if (specs[i].name == name)
      return static_cast<ParamId>(i);
  }
  return std::nullopt;
}

std::string paramIdToString(const std::array<char, 16>& field) {
  const auto end = std::find(field.begin(), field.end(), '\0');
  return std::string(field.begin(), end);
}

std::array<char, 16> paramIdField(std::string_view name) {
  std::array<char, 16> field{};
  std::copy_n(name.begin(), std::min(name.size(), field.size()), field.begin());
  return field;
}

ParamTable::ParamTable() {
  const auto& specs = paramSpecs();
  for (std::size_t i = 0; i < specs.size(); ++i) {
    min_[i] = specs[i].min;
    max_[i] = specs[i].max;
    values_[i] = specs[i].min;
  }
}

std::optional<std::string> ParamTable::set(ParamId id, double value) {
  const std::size_t i = index(id);
  const std::string name(paramSpecs()[i].name);
  if (!std::isfinite(value))
    return name + ": value is not a number";
  // float on the wire: accept values that round to the bounds.
  const double slack = 1e-6 * std::max(1.0, std::abs(max_[i]));
  if (value < min_[i] - slack || value > max_[i] + slack) {
    char text[96];
    std::snprintf(text, sizeof text, "%s: %.6g outside [%.6g, %.6g]", name.c_str(), value, min_[i],
                  max_[i]);
    return std::string(text);
  }
  values_[i] = std::clamp(value, min_[i], max_[i]);
  return std::nullopt;
}

void ParamTable::setRange(ParamId id, double min, double max) {
  if (!std::isfinite(min) || !std::isfinite(max) || min > max)
    throw std::invalid_argument("ParamTable::setRange: need finite min <= max");
  const std::size_t i = index(id);
  min_[i] = min;
  max_[i] = max;
  values_[i] = std::clamp(values_[i], min, max);
}

void ParamTable::setInitial(ParamId id, double value) {
  const std::size_t i = index(id);
  values_[i] = std::clamp(std::isfinite(value) ? value : min_[i], min_[i], max_[i]);
}

}  // namespace irgs::app
