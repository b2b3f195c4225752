#pragma once
// The firmware's onboard parameters (MAVLink parameter protocol, docs/protocol.md section 12):
// a fixed table of named float values with their ranges. Pure data; FirmwareCore answers
// PARAM_REQUEST_LIST / PARAM_REQUEST_READ / PARAM_SET from it and applies the values.
//
// Values are SI (seconds, metres per second, radians per second, hertz). Every parameter is
// MAV_PARAM_TYPE_REAL32 on the wire.

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace irgs::app {

enum class ParamId : std::size_t {
  kTeleopTimeout,  // TELEOP_TIMEOUT [s]: MANUAL_CONTROL validity
  kHbTimeout,      // HB_TIMEOUT [s]: ground-station heartbeat loss -> all motion stops
  kMaxSpeed,       // MAX_SPEED [m/s]: teleop full stick and behaviour speed cap
  kMaxTurnRate,    // MAX_TURN_RATE [rad/s]
  kRatePose,       // SR_POSE [Hz]: LOCAL_POSITION_NED, ATTITUDE, ODOMETRY, ticks, IRGS_POSE_2D
  kRateSonar,      // SR_SONAR [Hz]: DISTANCE_SENSOR, IRGS_SONAR_SCAN
  kRateContact,    // SR_CONTACT [Hz]: IRGS_CONTACT
  kRateImu,        // SR_IMU [Hz]: SCALED_IMU
  kRateStatus,     // SR_STATUS [Hz]: SYS_STATUS
  kCount
};

struct ParamSpec {
  std::string_view name;  // at most 16 characters (the wire field)
  double min = 0.0;
  double max = 0.0;
  std::string_view unit;
  std::string_view description;
};

// The table, in index order (PARAM_VALUE.param_index).
const std::array<ParamSpec, static_cast<std::size_t>(ParamId::kCount)>& paramSpecs();

// Index of a parameter by its wire name (exact, case-sensitive as MAVLink ids are).
std::optional<ParamId> findParam(std::string_view name);

// The name in a 16-byte MAVLink param_id field (NUL-terminated unless exactly 16 long).
std::string paramIdToString(const std::array<char, 16>& field);
std::array<char, 16> paramIdField(std::string_view name);

// The values with their ranges; the speed limits' upper bounds come from the robot profile.
class ParamTable {
 public:
  ParamTable();

  double get(ParamId id) const { return values_[index(id)]; }
  double min(ParamId id) const { return min_[index(id)]; }
  double max(ParamId id) const { return max_[index(id)]; }
  // Sets a value inside its range. Returns why not (non-finite, out of range) or nothing.
  std::optional<std::string> set(ParamId id, double value);
  // Narrows the range (the profile's limits); throws std::invalid_argument when min > max or
  // either is not finite. The value is clamped into the new range.
  void setRange(ParamId id, double min, double max);
  // Initial value from the firmware config, clamped into the range.
  void setInitial(ParamId id, double value);
  static constexpr std::size_t size() { return static_cast<std::size_t>(ParamId::kCount); }

 private:
  static std::size_t index(ParamId id) { return static_cast<std::size_t>(id); }

  std::array<double, static_cast<std::size_t>(ParamId::kCount)> values_{};
  std::array<double, static_cast<std::size_t>(ParamId::kCount)> min_{};
  std::array<double, static_cast<std::size_t>(ParamId::kCount)> max_{};
};

}  // namespace irgs::app
