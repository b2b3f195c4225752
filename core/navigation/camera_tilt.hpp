#pragma once
// How navigation uses the camera's tilt law. The law itself (A002-5: theta 35 deg far .. 90 deg
// overhead, linear in the landmark's horizontal distance) lives in one place,
// core/camera/tilt_servo.hpp (TiltLaw, tiltFromVertical, TiltServo); the robot profile's
// "ceiling_camera" section configures it (core/camera/ceiling_camera_config.hpp).

#include "core/camera/tilt_servo.hpp"

namespace irgs {

// 0 at the far tilt, 1 at the overhead tilt (clamped): how far the camera has risen, for
// slowing down as the robot closes in on a marker (Fig. 20).
double tiltRise(const TiltLaw& law, double tilt_rad);

}  // namespace irgs
