#pragma once
// Host-side conversions into the fixed-size vocabulary of the motion primitives: a robot
// profile's geometry and a telemetry sample's step input. (A firmware fills the same structs
// from its own tables and drivers.)

#include "core/motion/motion_geometry.hpp"
#include "core/motion/motion_input.hpp"
#include "core/robot/robot_profile.hpp"
#include "core/robot/telemetry.hpp"

namespace irgs::motion {

// Sonars beyond kMaxSonars are left out (no profile we know has more than 16).
MotionGeometry motionGeometryOf(const RobotProfile& profile);
// The sample's readings of sensors beyond kMaxSonars are left out.
MotionInput motionInputOf(const TelemetrySample& sample);

}  // namespace irgs::motion
