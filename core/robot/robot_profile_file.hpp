#pragma once
// Robot profiles as JSON files (resources/robots/*.json), read with located diagnostics.
//
// Format (version 1). Lengths in metres, angles in DEGREES (the file is written by people; the
// loaded RobotProfile holds radians), body frame x forward, y left, angles CCW from +x:
//
//   {
//     "format_version": 1,                       optional, must be 1
//     "name": "thesis_robot",                    required
//     "description": "...",                      optional
//     "notes": [...],                            optional free text, kept as is
//     "drive": { "type": "differential" | "three_caster" | "mouse_sensor",
//                "wheel_radius_m", "wheelbase_m" (required, > 0),
//                "encoder_counts_per_motor_rad", "gear_ratio" (optional, > 0) },
//     "limits": { "max_speed_mps", "max_turn_rate_degps", "max_accel_mps2",
//                 "max_turn_accel_degps2" (all optional, > 0) },
//     "body_outline": [[x, y], ...],              required, >= 3 points, simple polygon,
//                                                 either winding (stored counter-clockwise)
//     "sonars":    [{ "name", "x_m", "y_m", "heading_deg", "beam_width_deg" (0, 180],
//                     "min_range_m", "max_range_m", "rate_hz" }],
//     "bumpers":   [{ "name", "x_m", "y_m", "normal_deg", "half_width_m" }],   at most 32
//     "proximity": [{ "name", "x_m", "y_m", "heading_deg", "max_range_m", "rate_hz" }],
//     "calibration": { "odometry": {...}, "gyro": {...} }
//                  optional, written by the calibration wizards
//                  (core/calibration/profile_calibration.hpp)
//   }
//
// Sensor x_m, y_m and heading/normal are required; the other sensor fields default to the
// RobotProfile defaults. Unknown keys anywhere are kept (RobotProfile::extra and the `extra` of
// each part) and written back on save; they are reported as warnings so typos are noticed.

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/io/diagnostic.hpp"
#include "core/robot/robot_profile.hpp"

namespace irgs {

struct RobotProfileResult {
  std::optional<RobotProfile> profile;  // present when there is no error (warnings allowed)
  std::vector<Diagnostic> diagnostics;  // errors and warnings, in file order

  bool ok() const { return profile.has_value(); }
};

// Parses a profile from JSON text; `source_name` names the text in diagnostics.
RobotProfileResult parseRobotProfileJson(std::string_view text, const std::string& source_name);

// Reads and parses a profile file; an unreadable file is an error diagnostic.
RobotProfileResult loadRobotProfileFile(const std::filesystem::path& path);

// The file form of a profile (degrees, keys in a readable order, unknown keys restored).
nlohmann::ordered_json robotProfileToJson(const RobotProfile& profile);
// robotProfileToJson as indented text with a final newline.
std::string formatRobotProfileJson(const RobotProfile& profile);

// Writes the profile atomically. Returns nothing on success, otherwise the error.
std::optional<Diagnostic> saveRobotProfileFile(const RobotProfile& profile,
                                               const std::filesystem::path& path);

}  // namespace irgs
