#pragma once
// The three-caster steer/drive geometry of paper 000 (digest 1.4) read from a robot profile
// with drive type "three_caster" (resources/robots/caster3_000.json). The profile reader keeps
// the drive's unknown keys in DriveGeometry::extra; this reads its "three_caster" object:
//
//   "drive": { "type": "three_caster", "wheel_radius_m": r, ...,
//              "three_caster": { "caster_offset_m": eps (> 0),
//                                "casters": [ {"d_m": d_i (>= 0), "alpha_deg": alpha_i} x 3 ] } }
//
// (d_i, alpha_i) = polar coordinates of caster i's steering axis in the body frame (x forward,
// y left, alpha CCW from +x, degrees in the file).

#include <optional>
#include <vector>

#include "core/estimation/caster_odometry.hpp"
#include "core/io/diagnostic.hpp"
#include "core/robot/robot_profile.hpp"

namespace irgs {

struct CasterGeometryResult {
  std::optional<CasterDriveGeometry> geometry;  // present when there is no error
  std::vector<Diagnostic> diagnostics;          // field = JSON pointer into the profile file
};

CasterGeometryResult casterGeometryFromProfile(const RobotProfile& profile);

}  // namespace irgs
