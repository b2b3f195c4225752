#pragma once
// What a robot reports, simulated or linked. Units SI; poses in the world frame.

#include <cstdint>
#include <optional>
#include <vector>

#include "core/geometry/types.hpp"
#include "core/robot/caster_encoders.hpp"
#include "core/robot/mouse_counts.hpp"

namespace irgs {

// One sonar measurement. `range_m` is meaningful only when `echo` is true; without an echo
// the sonar saw nothing up to its maximum range (which is itself information: free space).
struct SonarReading {
  int sensor = 0;  // index into RobotProfile::sonars
  double range_m = 0.0;
  bool echo = false;
};

// One rate-gyro sample (paper 001_…): the gyro's raw indicated rate about body z (CCW positive,
// before any calibration) and the gyro's temperature, which drives its bias (A001-6).
struct GyroReading {
  double rate_radps = 0.0;
  double temperature_c = 25.0;
  bool saturated = false;  // the true rate was beyond the gyro's range; rate_radps is clipped
};

struct VelocityCommand {
  double linear_mps = 0.0;
  double angular_radps = 0.0;
  friend bool operator==(const VelocityCommand&, const VelocityCommand&) = default;
};

// A snapshot of the robot state at time_s. Sonar readings are those taken since the previous
// sample (each sonar fires at its own rate), so a consumer integrates every sample exactly once.
struct TelemetrySample {
  double time_s = 0.0;
  Pose2 odometry_pose;             // what the robot believes (dead reckoning)
  std::optional<Pose2> true_pose;  // ground truth, simulator only
  VelocityCommand measured_velocity;
  std::int64_t left_ticks = 0;  // cumulative encoder counts
  std::int64_t right_ticks = 0;
  std::vector<SonarReading> sonar;  // fresh readings taken at this sample's time
  std::uint32_t bumpers = 0;        // bit i = bumper i pressed
  std::vector<double> proximity_m;  // per proximity sensor; max range when nothing seen
  std::optional<GyroReading> gyro;  // present when the robot has a gyro
  // The robot reports its drive blocked: commanded but not moving (ARCOS SIP stall bits).
  // For robots without bumpers (Pioneers, AmigoBots) this is the only sign of a collision.
  bool drive_stalled = false;
  // Two optical floor sensors (paper 004), when present: counts since the start in each sensor's
  // axes (two samples' difference = that interval's report), status of the latest reading.
  std::optional<MouseReading> mouse;
  // The six encoders of a three-caster robot (paper 000), when the drive is "three_caster";
  // such a robot has no left/right wheels, so left_ticks and right_ticks stay 0.
  std::optional<CasterEncoders> casters;
};

// The body touches something: a bumper is pressed or the drive reports a stall.
inline bool inContact(const TelemetrySample& sample) {
  return sample.bumpers != 0 || sample.drive_stalled;
}

}  // namespace irgs
