#pragma once
// Deterministic, seeded, fixed-step simulation of a differential-drive robot in a WorldMap
// (vector walls/obstacles, or the map's raster layer), with odometry error and sonar, bumper
// and proximity sensors. Pure: no clocks, no threads; the caller decides how often to step.

#include <cstdint>
#include <memory>
#include <vector>

#include "core/robot/robot_profile.hpp"
#include "core/robot/telemetry.hpp"
#include "core/world/world_map.hpp"

namespace irgs {

struct OdometryErrorModel {
  double left_scale = 1.0;  // actual wheel travel / believed travel
  double right_scale = 1.0;
  double wheelbase_scale = 1.0;  // actual wheelbase / profile wheelbase
  double slip_stddev = 0.0;      // relative random slip per step, per wheel
};

struct SonarNoiseModel {
  double range_stddev_m = 0.005;
  double range_stddev_per_m = 0.005;  // extra stddev growing with range
  double dropout_probability = 0.01;  // echo missing at random
  // Beyond this incidence angle (between the ray and the surface normal) a specular surface
  // returns no echo to the sensor.
  double max_incidence_rad = degToRad(60.0);
  int rays_per_cone = 11;  // rays spread evenly across the beam, nearest return wins
};

struct SimConfig {
  double dt_s = 0.01;  // fixed step
  std::uint64_t seed = 1;
  OdometryErrorModel odometry;
  SonarNoiseModel sonar;
  double proximity_stddev_m = 0.002;
};

class Simulator {
 public:
  Simulator(WorldMap map, RobotProfile profile, SimConfig config);
  ~Simulator();
  Simulator(Simulator&&) noexcept;
  Simulator& operator=(Simulator&&) noexcept;

  // Sets the commanded body velocity; limits and accelerations of the profile apply.
  void setCommand(const VelocityCommand& command);
  // Advances one fixed step of config().dt_s and returns the sample for the new time.
  TelemetrySample step();

  // Replaces the world (e.g. after an edit) keeping the robot where it is.
  void setMap(WorldMap map);
  // Teleports the robot; odometry restarts from the same pose.
  void resetPose(const Pose2& pose);

  double time_s() const;
  const Pose2& truePose() const;
  const Pose2& odometryPose() const;
  const WorldMap& map() const;
  const RobotProfile& profile() const;
  const SimConfig& config() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace irgs
