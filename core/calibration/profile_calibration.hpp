#pragma once
// Calibration results stored in a robot profile (the profile file's documented "calibration"
// object, see docs/calibration.md), and writing the corrected profile.
//
//   "calibration": {
//     "odometry": { "method": "UMBmark", "left_wheel_scale", "right_wheel_scale",
//                   "wheel_diameter_ratio", "wheelbase_ratio", "side_m", "runs",
//                   "e_max_syst_m", "previous_wheelbase_m" },
//     "gyro": { "bias_c0_dps", "bias_c1_dps_per_c", "bias_c2_dps_per_c2",
//               "sf_a1", "sf_a2_per_dps", "sf_a3_per_dps2" }
//   }
//
// left/right_wheel_scale multiply the wheel travel the encoders report (wheel_radius_m is the
// mean wheel); the corrected wheelbase is written to drive.wheelbase_m itself.

#include <filesystem>
#include <optional>
#include <string>

#include "core/calibration/umbmark.hpp"
#include "core/estimation/gyro_calibration.hpp"
#include "core/robot/robot_profile.hpp"

namespace irgs {

// The odometry parameters a profile asks for: its per-wheel scales (1 when absent) and its
// wheelbase. A malformed "calibration.odometry" (non-numbers, scales <= 0) gives `error` and
// the uncalibrated values.
struct ProfileOdometry {
  OdometryCorrection odometry;
  std::string error;  // empty when fine
};
ProfileOdometry profileOdometry(const RobotProfile& profile);

// The gyro calibration stored in the profile, if any (nothing when absent or malformed).
std::optional<GyroCalibration> profileGyroCalibration(const RobotProfile& profile);

// A copy of `profile` with the UMBmark corrections applied (correctOdometry on the profile's
// current odometry) and recorded. Throws std::invalid_argument unless analysis.ok.
RobotProfile applyUmbmark(const RobotProfile& profile, const UmbmarkAnalysis& analysis,
                          double side_m);

// A copy of `profile` with the gyro calibration recorded. Throws std::invalid_argument for
// non-finite coefficients.
RobotProfile applyGyroCalibration(const RobotProfile& profile, const GyroCalibration& calibration);

// Writes the profile file atomically (core/io/atomic_file.hpp), creating missing folders.
// Returns nothing on success, otherwise the error.
std::optional<std::string> saveCalibratedProfile(const RobotProfile& profile,
                                                 const std::filesystem::path& path);

}  // namespace irgs
