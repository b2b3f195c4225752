#pragma once
// One control step's input to the robot-side motion primitives: the odometry pose, the measured
// velocity, the sonar readings taken since the previous step, the contact sensors. Fixed size
// (a firmware fills it from its drivers every control period; the host converts a
// TelemetrySample with motion_input_sample.hpp).

#include <array>
#include <cstdint>

#include "core/geometry/types.hpp"
#include "core/motion/motion_geometry.hpp"
#include "core/robot/telemetry.hpp"

namespace irgs::motion {

struct MotionInput {
  double time_s = 0.0;
  Pose2 odometry;
  VelocityCommand measured;  // v forward, omega CCW
  std::array<SonarReading, kMaxSonars> sonar{};
  std::uint8_t sonar_count = 0;
  std::uint32_t bumpers = 0;  // bit i = bumper i pressed
  bool stalled = false;       // the drive reports itself blocked (ARCOS stall bits)

  bool inContact() const { return bumpers != 0 || stalled; }
  bool addSonar(const SonarReading& r) {
    if (sonar_count >= kMaxSonars)
      return false;
    sonar[sonar_count++] = r;
    return true;
  }
};

}  // namespace irgs::motion
