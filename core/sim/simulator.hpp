#pragma once
// Deterministic, seeded, fixed-step simulation of a differential-drive robot (or the
// three-caster robot of paper 000, caster_drive_sim.hpp) in a WorldMap
// (vector walls/obstacles, or the map's raster layer), with odometry error and sonar, bumper
// and proximity sensors. Pure: no clocks, no threads; the caller decides how often to step.
//
// Model (details and the reasons in docs/decisions/simulator.md):
// * Drive: the commanded (v, omega) is clamped to the profile's limits and approached at the
//   profile's accelerations; the wheels turn as the nominal kinematics ask (diff_drive.hpp).
// * Truth vs belief: encoders count the wheel rotation (quantised ticks); odometry integrates
//   ticks with the NOMINAL wheel radius and wheelbase. The true motion scales each wheel's
//   ground travel by the error model's scale factor and random slip and uses the TRUE wheelbase,
//   so odometry drifts from truth exactly as configured.
// * Collisions: the body polygon never penetrates geometry. A step that would is cut to the
//   largest fraction that does not (bisection); the robot then stalls (velocity 0) and the
//   encoders count only the travel made. Wheels held still while driven for 0.2 s make the
//   sample report the drive stalled (drive_stalled), as a Pioneer's stall bits do. A robot placed
//   overlapping geometry may move freely until it is clear. An empty body outline is a point robot
//   that never collides.
// * Sensors fire at their own rates; sensor i of n first fires at (i + 1) / n of its period, so
//   they do not all fire in one step; at most one firing per sensor per step.
// * Random numbers: one independent SimRandom stream per purpose (motion, sonar, proximity,
//   gyro), all derived from SimConfig::seed (random.hpp): the same seed gives identical samples, a
//   different seed different noise. The random draws are bit-identical on every platform; the
//   trigonometry of the motion comes from the platform's libm.

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "core/estimation/mouse_sensor.hpp"
#include "core/robot/robot_profile.hpp"
#include "core/robot/telemetry.hpp"
#include "core/sim/caster_drive_sim.hpp"
#include "core/sim/gyro_sim.hpp"
#include "core/sim/sim_world.hpp"
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
  // Ray caster for the vector segments (kNaive only for benchmarks and tests).
  SegmentCasterKind segment_caster = SegmentCasterKind::kIndexed;
  // Which raster cells are solid (see solid_raster.hpp: unknown cells are solid by default).
  RasterSolidity raster;
  // A bumper reports contact when geometry is this close to its bar (the switch's travel).
  double bumper_contact_m = 0.002;
  // A yaw rate gyro (gyro_sim.hpp), read every step from its own random stream. Disabled by
  // default: then samples carry no GyroReading and every other output is unchanged.
  GyroErrorModel gyro;
  // Two optical floor (mouse) sensors of paper 004, simulated when the profile has a
  // drive/mouse_sensors rig (and this is true), read every step from their own random stream;
  // without a rig samples carry no MouseReading and every other output is unchanged.
  bool mouse_sensors = true;
  MouseNoise mouse_noise;
  double mouse_floor_gap_m = 0.0;  // sensor-to-floor gap; above the rig's max_lift_m: no counts
  // The three-caster robot of paper 000 (profiles with drive type "three_caster"; see
  // caster_drive_sim.hpp): its wheel errors, empty = the profile's
  // drive/three_caster/simulated_errors; and the period its kinematics and its own J+ dead
  // reckoning run at within each step [000: 1 ms]. The motion's random numbers come from their
  // own stream (6). The differential-drive `odometry` errors do not apply to it.
  std::optional<CasterErrorModel> caster_errors;
  double caster_period_s = 0.001;
};

class Simulator {
 public:
  // Throws std::invalid_argument for a config or profile the model cannot run (dt <= 0,
  // non-positive wheel radius, a sonar with min_range >= max_range, ...).
  Simulator(WorldMap map, RobotProfile profile, SimConfig config);
  ~Simulator();
  Simulator(Simulator&&) noexcept;
  Simulator& operator=(Simulator&&) noexcept;

  // Sets the commanded body velocity; limits and accelerations of the profile apply.
  // Throws std::invalid_argument for non-finite values.
  void setCommand(const VelocityCommand& command);
  // Stops the wheels at once, bypassing the acceleration limits (an emergency brake, as a
  // firmware safety stop does): command and body velocity become zero; poses are kept.
  void halt();
  // Advances one fixed step of config().dt_s and returns the sample for the new time.
  TelemetrySample step();
  // step() writing into `sample`, reusing its vectors' capacity (no allocation once warm).
  void step(TelemetrySample& sample);

  // Replaces the world (e.g. after an edit) keeping the robot where it is.
  void setMap(WorldMap map);
  // Teleports the robot; odometry restarts from the same pose. The robot stops (the command is
  // cleared). Throws std::invalid_argument for a non-finite pose.
  void resetPose(const Pose2& pose);

  double time_s() const;
  const Pose2& truePose() const;
  const Pose2& odometryPose() const;
  const WorldMap& map() const;
  const RobotProfile& profile() const;
  const SimConfig& config() const;

  const VelocityCommand& command() const;
  // The true body velocity during the last step (after limits, accelerations and collisions).
  VelocityCommand trueVelocity() const;
  // Bumper bits of the last step (bit i = profile().bumpers[i]).
  std::uint32_t bumpers() const;
  std::int64_t stepCount() const;
  const SimWorld& world() const;
  // Outlines (world frame) of the map's moving obstacles now, in map order.
  const std::vector<std::vector<Vec2>>& movingObstaclePolygons() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace irgs
