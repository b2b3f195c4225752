#pragma once
// The ceiling camera a robot carries: intrinsics, mount, tilt law and working range. Stored in
// the robot profile as the documented "ceiling_camera" object (docs/landmark-navigation.md):
//
//   "ceiling_camera": {
//     "width_px": 640, "height_px": 480, "fx_px": 554.3, "fy_px": 554.3,
//     "cx_px": 319.5, "cy_px": 239.5, "skew": 0,
//     "mount": { "x_m": 0.1, "y_m": 0.0, "z_m": 0.5 },
//     "tilt": { "min_deg": 35, "max_deg": 90, "near_m": 0.3, "far_m": 4.0, "rate_degps": 90 },
//     "working_range_m": 4.0,
//     "ceiling_height_m": 2.6          (optional: overrides the map's ceiling height)
//   }
//
// Every key is optional; absent keys keep the defaults below.

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/camera/camera_model.hpp"
#include "core/camera/tilt_servo.hpp"
#include "core/robot/robot_profile.hpp"

namespace irgs {

struct CeilingCameraConfig {
  CameraIntrinsics intrinsics;
  CameraMount mount;
  TiltLaw tilt;
  double tilt_rate_radps = 1.5707963267948966;  // 90 deg/s
  // Horizontal distance from the camera up to which markers must be found (the acceptance
  // range of the detector; farther markers may be found too).
  double working_range_m = 4.0;
  std::optional<double> ceiling_height_m;  // overrides the map's when set

  // The ceiling height to use with a map whose ceiling is `map_ceiling_m` high.
  double ceilingHeight(double map_ceiling_m) const {
    return ceiling_height_m.value_or(map_ceiling_m);
  }
};

struct CeilingCameraConfigResult {
  CeilingCameraConfig config;       // defaults where a key is absent or wrong
  std::vector<std::string> errors;  // "field: message", empty when fine
};

// Reads a "ceiling_camera" object (see above).
CeilingCameraConfigResult ceilingCameraFromJson(const nlohmann::json& object);
// The profile's "ceiling_camera" (kept in RobotProfile::extra by the profile loader); defaults
// when the profile has none.
CeilingCameraConfigResult ceilingCameraFromProfile(const RobotProfile& profile);
nlohmann::json ceilingCameraToJson(const CeilingCameraConfig& config);

}  // namespace irgs
