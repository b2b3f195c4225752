#pragma once
// A robot description: drive geometry, limits, body outline and sensors with their mounts.
// Loaded from JSON (robot_profile_file.hpp); bundled profiles live in resources/robots/.

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/geometry/types.hpp"

namespace irgs {

enum class DriveType { kDifferential, kThreeCaster, kMouseSensor };

struct DriveGeometry {
  DriveType type = DriveType::kDifferential;
  double wheel_radius_m = 0.035;
  double wheelbase_m = 0.25;  // full separation of the drive wheels (A003-1)
  // Encoder counts per radian of the *motor* shaft and the motor:wheel gear ratio; ticks per
  // wheel radian = counts_per_motor_rad * gear_ratio (003_…: 27 pulse/rad, 1:100).
  double encoder_counts_per_motor_rad = 27.0;
  double gear_ratio = 100.0;

  double ticksPerWheelRad() const { return encoder_counts_per_motor_rad * gear_ratio; }
  double metresPerTick() const { return wheel_radius_m / ticksPerWheelRad(); }

  nlohmann::json extra = nlohmann::json::object();  // unknown keys, preserved on save
};

struct MotionLimits {
  double max_speed_mps = 0.4;
  double max_turn_rate_radps = 1.5;
  double max_accel_mps2 = 0.8;
  double max_turn_accel_radps2 = 4.0;

  nlohmann::json extra = nlohmann::json::object();  // unknown keys, preserved on save
};

// An ultrasonic range sensor. Mount pose is in the body frame.
struct SonarSpec {
  std::string name;
  Pose2 mount;
  double beam_width_rad = degToRad(25.0);  // full cone angle
  double min_range_m = 0.03;
  double max_range_m = 4.0;
  double rate_hz = 10.0;                            // how often this sonar fires
  nlohmann::json extra = nlohmann::json::object();  // unknown keys, preserved on save
};

// A contact switch on the body: triggers when the body edge near `position` touches.
struct BumperSpec {
  std::string name;
  Vec2 position = Vec2::Zero();  // on the body outline, body frame
  double normal_rad = 0.0;       // outward normal of the face it sits on
  double half_width_m = 0.05;    // the bar widening its sensing area along the face
  nlohmann::json extra = nlohmann::json::object();
};

// An infrared proximity (photo) sensor: a short single ray, read as a distance.
struct ProximitySpec {
  std::string name;
  Pose2 mount;
  double max_range_m = 0.3;
  double rate_hz = 20.0;  // how often the reading is refreshed
  nlohmann::json extra = nlohmann::json::object();
};

struct RobotProfile {
  std::string name;
  std::string description;
  DriveGeometry drive;
  MotionLimits limits;
  std::vector<Vec2> body_outline;  // body frame, counter-clockwise polygon
  std::vector<SonarSpec> sonars;
  std::vector<BumperSpec> bumpers;
  std::vector<ProximitySpec> proximity;
  nlohmann::json extra = nlohmann::json::object();  // unknown keys, preserved on save

  // Radius of the smallest circle about the body origin that contains the outline.
  double bodyRadius() const;
};

}  // namespace irgs
