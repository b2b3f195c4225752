#include "core/sim/simulator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include "core/estimation/caster_profile.hpp"
#include "core/estimation/mouse_odometry.hpp"
#include "core/geometry/geometry_queries.hpp"
#include "core/sim/diff_drive.hpp"
#include "core/sim/random.hpp"
#include "core/world/moving_obstacle.hpp"

namespace irgs {

namespace {

// Independent random streams (SimRandom::stream purposes).
constexpr std::uint64_t kMotionStream = 1;
constexpr std::uint64_t kSonarStream = 2;
constexpr std::uint64_t kProximityStream = 3;
constexpr std::uint64_t kGyroStream = 4;
constexpr std::uint64_t kMouseStream = 5;
constexpr std::uint64_t kCasterStream = 6;

// Bisection steps when a step would penetrate: the remaining gap is below step * 2^-16.
constexpr int kCollisionBisections = 16;
// Clearance is searched this far beyond what the body and the proximity rays can reach, so a
// robot in open space re-checks only every kClearanceSlack_m of travel.
constexpr double kClearanceSlack_m = 0.25;
// A moving obstacle waits while its next position would come this close to the robot's body.
constexpr double kMoverYield_m = 0.05;
// The drive reports a stall (TelemetrySample::drive_stalled) once its wheels, driven faster than
// kDrivenSpeed (m/s or rad/s), made less than kStalledFraction of their step for kStallAfter_s.
constexpr double kDrivenSpeed = 1e-3;
constexpr double kStalledFraction = 0.5;
constexpr double kStallAfter_s = 0.2;
// A sensor is due when its time has come within this much (absorbs t = n * dt rounding).
constexpr double kScheduleEpsilon_s = 1e-9;

void require(bool condition, const std::string& what) {
  if (!condition)
    throw std::invalid_argument("Simulator: " + what);
}

bool finite(double v) {
  return std::isfinite(v);
}

void validate(const RobotProfile& p, const SimConfig& c) {
  require(finite(c.dt_s) && c.dt_s > 0.0 && c.dt_s <= 1.0, "dt_s must be in (0, 1] s");
  require(c.sonar.rays_per_cone >= 1 && c.sonar.rays_per_cone <= 1000,
          "rays_per_cone must be in [1, 1000]");
  require(finite(c.sonar.range_stddev_m) && c.sonar.range_stddev_m >= 0.0 &&
              finite(c.sonar.range_stddev_per_m) && c.sonar.range_stddev_per_m >= 0.0,
          "sonar noise stddevs must be finite and >= 0");
  require(c.sonar.dropout_probability >= 0.0 && c.sonar.dropout_probability <= 1.0,
          "dropout_probability must be in [0, 1]");
  require(c.sonar.max_incidence_rad >= 0.0 && c.sonar.max_incidence_rad <= kPi / 2.0,
          "max_incidence_rad must be in [0, pi/2]");
  require(finite(c.proximity_stddev_m) && c.proximity_stddev_m >= 0.0,
          "proximity_stddev_m must be finite and >= 0");
  const OdometryErrorModel& o = c.odometry;
  require(finite(o.left_scale) && o.left_scale > 0.0 && finite(o.right_scale) &&
              o.right_scale > 0.0 && finite(o.wheelbase_scale) && o.wheelbase_scale > 0.0,
          "odometry scale factors must be finite and > 0");
  require(finite(o.slip_stddev) && o.slip_stddev >= 0.0, "slip_stddev must be finite and >= 0");
  require(finite(c.bumper_contact_m) && c.bumper_contact_m >= 0.0,
          "bumper_contact_m must be finite and >= 0");

  const DriveGeometry& d = p.drive;
  require(finite(d.wheel_radius_m) && d.wheel_radius_m > 0.0, "wheel_radius_m must be > 0");
  require(finite(d.wheelbase_m) && d.wheelbase_m > 0.0, "wheelbase_m must be > 0");
  require(finite(d.ticksPerWheelRad()) && d.ticksPerWheelRad() > 0.0,
          "encoder counts and gear ratio must be > 0");
  const MotionLimits& l = p.limits;
  require(finite(l.max_speed_mps) && l.max_speed_mps > 0.0 && finite(l.max_turn_rate_radps) &&
              l.max_turn_rate_radps > 0.0 && finite(l.max_accel_mps2) && l.max_accel_mps2 > 0.0 &&
              finite(l.max_turn_accel_radps2) && l.max_turn_accel_radps2 > 0.0,
          "motion limits must be finite and > 0");
  for (const Vec2& v : p.body_outline)
    require(finite(v.x()) && finite(v.y()), "body outline has a non-finite point");
  for (const SonarSpec& s : p.sonars) {
    require(finite(s.mount.x) && finite(s.mount.y) && finite(s.mount.theta),
            "sonar " + s.name + ": non-finite mount");
    require(s.beam_width_rad >= 0.0 && s.beam_width_rad <= kPi,
            "sonar " + s.name + ": beam width must be in [0, pi]");
    require(s.min_range_m >= 0.0 && s.max_range_m > s.min_range_m && finite(s.max_range_m),
            "sonar " + s.name + ": needs 0 <= min_range < max_range");
    require(finite(s.rate_hz) && s.rate_hz > 0.0, "sonar " + s.name + ": rate_hz must be > 0");
  }
  require(p.bumpers.size() <= 32, "at most 32 bumpers");
  for (const BumperSpec& b : p.bumpers)
    require(finite(b.position.x()) && finite(b.position.y()) && finite(b.normal_rad) &&
                finite(b.half_width_m) && b.half_width_m >= 0.0,
            "bumper " + b.name + ": non-finite or negative geometry");
  for (const ProximitySpec& s : p.proximity) {
    require(finite(s.mount.x) && finite(s.mount.y) && finite(s.mount.theta),
            "proximity " + s.name + ": non-finite mount");
    require(finite(s.max_range_m) && s.max_range_m > 0.0,
            "proximity " + s.name + ": max_range_m must be > 0");
    require(finite(s.rate_hz) && s.rate_hz > 0.0, "proximity " + s.name + ": rate_hz must be > 0");
  }
}

double approach(double current, double target, double max_change) {
  return current + std::clamp(target - current, -max_change, max_change);
}

Vec2 rotate(const Vec2& v, double c, double s) {
  return {c * v.x() - s * v.y(), s * v.x() + c * v.y()};
}

}  // namespace

struct Simulator::Impl {
  struct SonarState {
    std::vector<Vec2> ray_dirs_body;  // unit ray directions in the body frame
    double period_s = 0.1;
    double next_fire_s = 0.0;
  };
  struct ProximityState {
    Vec2 dir_body = Vec2::UnitX();
    double reach_m = 0.0;  // farthest point of the ray from the body origin
    double period_s = 0.05;
    double next_s = 0.0;
    double value_m = 0.0;
  };

  WorldMap map;
  RobotProfile profile;
  SimConfig config;
  std::unique_ptr<SimWorld> world;
  SimRandom motion_rng;
  SimRandom sonar_rng;
  SimRandom proximity_rng;
  std::optional<GyroSimulator> gyro;  // present when config.gyro.enabled
  // The right and left floor sensors, present when the profile has a mouse rig.
  std::optional<std::pair<MouseSensorSimulator, MouseSensorSimulator>> mice;
  SimRandom mouse_rng;
  MouseReading mouse_total;                     // counts since the start, in each sensor's axes
  std::optional<CasterDriveSimulator> casters;  // drive type "three_caster"
  SimRandom caster_rng;

  Pose2 true_pose;
  Pose2 odom_pose;
  VelocityCommand command;
  double v_mps = 0.0;  // body velocity the wheels are driven at (after limits/acceleration)
  double omega_radps = 0.0;
  VelocityCommand true_velocity;
  double left_wheel_rad = 0.0;  // cumulative wheel rotation
  double right_wheel_rad = 0.0;
  std::int64_t left_ticks = 0;
  std::int64_t right_ticks = 0;
  std::int64_t steps = 0;
  std::uint32_t bumper_bits = 0;

  double body_radius = 0.0;
  double clearance_cap = 0.0;
  double clearance = 0.0;        // lower bound of the distance from the body origin to any geometry
  bool clearance_fresh = false;  // computed at the current true pose

  std::vector<SonarState> sonars;
  std::vector<ProximityState> proximity;
  std::vector<double> mover_distance;  // metres travelled along each moving obstacle's path
  std::vector<std::vector<Vec2>> mover_polygons;  // world frame, now
  double cos_max_incidence = 0.5;

  // Scratch, reused every step.
  std::vector<Vec2> body_world;
  std::vector<Vec2> ray_dirs_world;
  std::vector<std::optional<RayHit>> hits;

  Impl(WorldMap m, RobotProfile p, SimConfig c)
      : map(std::move(m)),
        profile(std::move(p)),
        config(c),
        motion_rng(SimRandom::stream(c.seed, kMotionStream)),
        sonar_rng(SimRandom::stream(c.seed, kSonarStream)),
        proximity_rng(SimRandom::stream(c.seed, kProximityStream)),
        mouse_rng(SimRandom::stream(c.seed, kMouseStream)),
        caster_rng(SimRandom::stream(c.seed, kCasterStream)) {
    validate(profile, config);
    makeCasters();
    if (config.gyro.enabled)
      gyro.emplace(config.gyro, SimRandom::stream(c.seed, kGyroStream));
    makeMice();
    require(
        std::isfinite(map.start.x) && std::isfinite(map.start.y) && std::isfinite(map.start.theta),
        "the map's start pose is not finite");
    buildWorld();
    true_pose = odom_pose = Pose2{map.start.x, map.start.y, wrapAngle(map.start.theta)};
    body_radius = profile.bodyRadius();
    cos_max_incidence = std::cos(config.sonar.max_incidence_rad);

    const int n_rays = config.sonar.rays_per_cone;
    const std::size_t n_sonars = profile.sonars.size();
    for (std::size_t i = 0; i < n_sonars; ++i) {
      const SonarSpec& spec = profile.sonars[i];
      SonarState state;
      for (int k = 0; k < n_rays; ++k) {
        const double offset =
            n_rays == 1 ? 0.0 : spec.beam_width_rad * (static_cast<double>(k) / (n_rays - 1) - 0.5);
        const double a = spec.mount.theta + offset;
        state.ray_dirs_body.emplace_back(std::cos(a), std::sin(a));
      }
      state.period_s = 1.0 / spec.rate_hz;
      state.next_fire_s =
          state.period_s * static_cast<double>(i + 1) / static_cast<double>(n_sonars);
      sonars.push_back(std::move(state));
    }
    double reach = body_radius;
    const std::size_t n_prox = profile.proximity.size();
    for (std::size_t i = 0; i < n_prox; ++i) {
      const ProximitySpec& spec = profile.proximity[i];
      ProximityState state;
      state.dir_body = {std::cos(spec.mount.theta), std::sin(spec.mount.theta)};
      state.reach_m = Vec2(spec.mount.x, spec.mount.y).norm() + spec.max_range_m;
      state.period_s = 1.0 / spec.rate_hz;
      state.next_s = state.period_s * static_cast<double>(i + 1) / static_cast<double>(n_prox);
      state.value_m = spec.max_range_m;
      reach = std::max(reach, state.reach_m);
      proximity.push_back(state);
    }
    clearance_cap = reach + kClearanceSlack_m;
    hits.resize(static_cast<std::size_t>(n_rays));
    ray_dirs_world.resize(static_cast<std::size_t>(n_rays));
  }

  void buildWorld() {
    world = std::make_unique<SimWorld>(map, SimWorldOptions{config.segment_caster, config.raster});
    clearance_fresh = false;
    clearance = 0.0;
    mover_distance.assign(map.moving_obstacles.size(), 0.0);
    placeMovers();
  }

  void placeMovers() {
    mover_polygons.resize(map.moving_obstacles.size());
    for (std::size_t i = 0; i < mover_polygons.size(); ++i) {
      const MovingObstacle& m = map.moving_obstacles[i];
      mover_polygons[i] = movingObstaclePolygon(m, movingObstacleAt(m, mover_distance[i]));
    }
    world->setMovingPolygons(mover_polygons);
  }

  // Distance between two polygons (0 when they touch or one holds the other).
  static double polygonDistance(std::span<const Vec2> a, std::span<const Vec2> b) {
    if (a.empty() || b.empty())
      return std::numeric_limits<double>::infinity();
    if (pointInPolygon(a[0], b) || pointInPolygon(b[0], a))
      return 0.0;
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < a.size(); ++i) {
      for (std::size_t j = 0; j < b.size(); ++j)
        best = std::min(
            best, segmentSegmentDistance(a[i], a[(i + 1) % a.size()], b[j], b[(j + 1) % b.size()]));
    }
    return best;
  }

  // Moves every scripted obstacle on by one step. An obstacle whose next position would come
  // within kMoverYield_m of the robot waits (people and carts stop for a robot), so every
  // contact is one the robot drives into.
  void moveMovers(double now) {
    if (map.moving_obstacles.empty())
      return;
    const auto& outline = profile.body_outline;
    body_world.resize(outline.size());
    for (std::size_t i = 0; i < outline.size(); ++i)
      body_world[i] = true_pose.toWorld(outline[i]);
    for (std::size_t i = 0; i < mover_polygons.size(); ++i) {
      const MovingObstacle& m = map.moving_obstacles[i];
      if (now <= m.start_delay_s)
        continue;
      const double next = mover_distance[i] + m.speed_mps * config.dt_s;
      std::vector<Vec2> polygon = movingObstaclePolygon(m, movingObstacleAt(m, next));
      if (polygonDistance(polygon, body_world) <= kMoverYield_m)
        continue;
      mover_distance[i] = next;
      mover_polygons[i] = std::move(polygon);
    }
    world->setMovingPolygons(mover_polygons);
    clearance_fresh = false;  // the world moved: the cached bound no longer holds
    clearance = 0.0;
  }

  double time() const { return static_cast<double>(steps) * config.dt_s; }

  void refreshClearance() {
    if (!clearance_fresh) {
      clearance = world->clearanceLowerBound(true_pose.position(), clearance_cap);
      clearance_fresh = true;
    }
  }

  // True when nothing can be within `margin` of the body disc (radius body_radius).
  bool clearBeyond(double margin) {
    if (clearance > body_radius + margin)
      return true;
    refreshClearance();
    return clearance > body_radius + margin;
  }

  bool bodyTouchesAt(const Pose2& pose) {
    const auto& outline = profile.body_outline;
    if (outline.empty())
      return false;
    body_world.resize(outline.size());
    for (std::size_t i = 0; i < outline.size(); ++i)
      body_world[i] = pose.toWorld(outline[i]);
    return world->polygonTouches(body_world);
  }

  // Moves the true pose by the arc (ds, dtheta), cut short where the body would touch geometry
  // (then the drive stalls, and reports it once that lasts); returns the fraction of the step made.
  double moveBody(double ds, double dtheta) {
    const double dt = config.dt_s;
    double fraction = 1.0;
    Pose2 next = integrateArc(true_pose, ds, dtheta);
    double travel = (next.position() - true_pose.position()).norm();
    if ((ds != 0.0 || dtheta != 0.0) && !profile.body_outline.empty() && !clearBeyond(travel) &&
        bodyTouchesAt(next) && !bodyTouchesAt(true_pose)) {
      // Largest fraction of the step that keeps the body off the geometry.
      double lo = 0.0, hi = 1.0;
      for (int i = 0; i < kCollisionBisections; ++i) {
        const double mid = 0.5 * (lo + hi);
        if (bodyTouchesAt(integrateArc(true_pose, mid * ds, mid * dtheta)))
          hi = mid;
        else
          lo = mid;
      }
      fraction = lo;
      next = integrateArc(true_pose, fraction * ds, fraction * dtheta);
      travel = (next.position() - true_pose.position()).norm();
      v_mps = 0.0;  // stalled against the obstacle
      omega_radps = 0.0;
    }
    true_velocity = {fraction * ds / dt, fraction * dtheta / dt};
    if (next != true_pose) {
      true_pose = next;
      clearance -= travel;
      clearance_fresh = false;
    }
    // Driven wheels held still by an obstacle: what a drive's stall detection (ARCOS stall bits,
    // a motor controller's current limit) reports once it lasts kStallAfter_s.
    const bool driven = std::abs(command.linear_mps) > kDrivenSpeed ||
                        std::abs(command.angular_radps) > kDrivenSpeed;
    stalled_s = driven && fraction < kStalledFraction ? stalled_s + dt : 0.0;
    return fraction;
  }

  // The three-caster robot: the body moves with the (limited) commanded twist, the casters
  // follow it and their encoders and the robot's J+ dead reckoning count what they did.
  void moveCasters() {
    const double dt = config.dt_s;
    moveBody(v_mps * dt, omega_radps * dt);
    const Pose2 odom_before = odom_pose;
    casters->advance(BodyTwist(true_velocity.linear_mps, 0.0, true_velocity.angular_radps), dt,
                     odom_pose, caster_rng);
    const BodyIncrement odo = incrementBetween(odom_before, odom_pose);
    measured_ds = odo.dx_m;
    measured_dtheta = odo.dtheta_rad;
  }

  void makeCasters() {
    casters.reset();
    if (profile.drive.type != DriveType::kThreeCaster)
      return;
    const CasterGeometryResult geometry = casterGeometryFromProfile(profile);
    if (!geometry.geometry) {
      const Diagnostic& d = geometry.diagnostics.front();
      throw std::invalid_argument("robot profile " + d.field + ": " + d.message);
    }
    CasterErrorModel errors;
    if (config.caster_errors) {
      errors = *config.caster_errors;
    } else {
      const CasterErrorResult from_profile = casterErrorsFromProfile(profile);
      if (!from_profile.errors) {
        const Diagnostic& d = from_profile.diagnostics.front();
        throw std::invalid_argument("robot profile " + d.field + ": " + d.message);
      }
      errors = *from_profile.errors;
    }
    require(std::isfinite(config.caster_period_s) && config.caster_period_s > 0.0,
            "caster_period_s must be finite and > 0");
    casters.emplace(*geometry.geometry, errors, profile.drive.ticksPerWheelRad(),
                    config.caster_period_s);
  }

  void move() {
    const double dt = config.dt_s;
    const MotionLimits& lim = profile.limits;
    const DriveGeometry& drive = profile.drive;
    const OdometryErrorModel& err = config.odometry;

    // Velocity the wheel controllers track: the command clamped to the limits, reached at the
    // profile's accelerations.
    const double target_v = std::clamp(command.linear_mps, -lim.max_speed_mps, lim.max_speed_mps);
    const double target_w =
        std::clamp(command.angular_radps, -lim.max_turn_rate_radps, lim.max_turn_rate_radps);
    v_mps = approach(v_mps, target_v, lim.max_accel_mps2 * dt);
    omega_radps = approach(omega_radps, target_w, lim.max_turn_accel_radps2 * dt);

    if (casters) {
      moveCasters();
      return;
    }
    // Wheel rotation this step from the nominal kinematics (what the encoders see).
    const WheelSpeeds wheels = wheelSpeeds(v_mps, omega_radps, drive.wheelbase_m);
    const double dphi_left = wheels.left_mps * dt / drive.wheel_radius_m;
    const double dphi_right = wheels.right_mps * dt / drive.wheel_radius_m;

    // True ground travel: scale factors, random slip, true wheelbase.
    double slip_left = 1.0, slip_right = 1.0;
    if (err.slip_stddev > 0.0) {
      slip_left += err.slip_stddev * motion_rng.gaussian();
      slip_right += err.slip_stddev * motion_rng.gaussian();
    }
    const double d_left = dphi_left * drive.wheel_radius_m * err.left_scale * slip_left;
    const double d_right = dphi_right * drive.wheel_radius_m * err.right_scale * slip_right;
    const double ds = 0.5 * (d_left + d_right);
    const double dtheta = (d_right - d_left) / (drive.wheelbase_m * err.wheelbase_scale);

    const double fraction = moveBody(ds, dtheta);

    // Encoders: quantised cumulative wheel rotation (floor, so counts are consistent in both
    // directions). Odometry: tick deltas through the NOMINAL model.
    left_wheel_rad += fraction * dphi_left;
    right_wheel_rad += fraction * dphi_right;
    const double ticks_per_rad = drive.ticksPerWheelRad();
    const auto new_left = static_cast<std::int64_t>(std::floor(left_wheel_rad * ticks_per_rad));
    const auto new_right = static_cast<std::int64_t>(std::floor(right_wheel_rad * ticks_per_rad));
    const double odo_left = static_cast<double>(new_left - left_ticks) * drive.metresPerTick();
    const double odo_right = static_cast<double>(new_right - right_ticks) * drive.metresPerTick();
    left_ticks = new_left;
    right_ticks = new_right;
    odom_pose = integrateArc(odom_pose, 0.5 * (odo_left + odo_right),
                             (odo_right - odo_left) / drive.wheelbase_m);
    measured_ds = 0.5 * (odo_left + odo_right);
    measured_dtheta = (odo_right - odo_left) / drive.wheelbase_m;
  }
  double measured_ds = 0.0;
  double measured_dtheta = 0.0;
  double stalled_s = 0.0;  // how long the driven wheels have been held still

  void updateBumpers() {
    bumper_bits = 0;
    if (profile.bumpers.empty() || clearBeyond(config.bumper_contact_m))
      return;
    for (std::size_t i = 0; i < profile.bumpers.size(); ++i) {
      const BumperSpec& b = profile.bumpers[i];
      const Vec2 along(-std::sin(b.normal_rad), std::cos(b.normal_rad));
      const Vec2 a = true_pose.toWorld(b.position - b.half_width_m * along);
      const Vec2 c = true_pose.toWorld(b.position + b.half_width_m * along);
      if (world->segmentWithin(a, c, config.bumper_contact_m))
        bumper_bits |= std::uint32_t{1} << i;
    }
  }

  bool due(double& next_s, double period_s, double now) {
    if (now + kScheduleEpsilon_s < next_s)
      return false;
    next_s += period_s;
    if (next_s <= now)  // faster than the step: at most one firing per step, no backlog
      next_s = now + period_s;
    return true;
  }

  void fireSonars(double now, double c, double s, std::vector<SonarReading>& out) {
    const SonarNoiseModel& noise = config.sonar;
    for (std::size_t i = 0; i < sonars.size(); ++i) {
      SonarState& state = sonars[i];
      if (!due(state.next_fire_s, state.period_s, now))
        continue;
      const SonarSpec& spec = profile.sonars[i];
      const Vec2 origin = true_pose.toWorld({spec.mount.x, spec.mount.y});
      for (std::size_t k = 0; k < state.ray_dirs_body.size(); ++k)
        ray_dirs_world[k] = rotate(state.ray_dirs_body[k], c, s);
      world->castFan(origin, ray_dirs_world, spec.max_range_m, hits);
      // Nearest return among the rays whose surface is not too oblique to echo back.
      double nearest = std::numeric_limits<double>::infinity();
      for (std::size_t k = 0; k < hits.size(); ++k) {
        const auto& hit = hits[k];
        if (hit && std::abs(hit->normal.dot(ray_dirs_world[k])) >= cos_max_incidence)
          nearest = std::min(nearest, hit->distance_m);
      }
      const bool dropped = sonar_rng.bernoulli(noise.dropout_probability);
      SonarReading reading{static_cast<int>(i), spec.max_range_m, false};
      if (!dropped && nearest <= spec.max_range_m) {
        const double stddev = noise.range_stddev_m + noise.range_stddev_per_m * nearest;
        reading.range_m =
            std::clamp(nearest + stddev * sonar_rng.gaussian(), spec.min_range_m, spec.max_range_m);
        reading.echo = true;
      }
      out.push_back(reading);
    }
  }

  void updateProximity(double now, double c, double s) {
    for (std::size_t i = 0; i < proximity.size(); ++i) {
      ProximityState& state = proximity[i];
      if (!due(state.next_s, state.period_s, now))
        continue;
      const ProximitySpec& spec = profile.proximity[i];
      state.value_m = spec.max_range_m;
      if (clearBeyond(state.reach_m - body_radius))
        continue;  // nothing within reach of this ray
      const Vec2 origin = true_pose.toWorld({spec.mount.x, spec.mount.y});
      if (const auto hit = world->cast(origin, rotate(state.dir_body, c, s), spec.max_range_m)) {
        state.value_m =
            std::clamp(hit->distance_m + config.proximity_stddev_m * proximity_rng.gaussian(), 0.0,
                       spec.max_range_m);
      }
    }
  }

  void makeMice() {
    mice.reset();
    if (!config.mouse_sensors || !profile.drive.extra.contains("mouse_sensors"))
      return;
    MouseRigResult rig = mouseRigFromProfile(profile);
    if (!rig.rig) {
      const Diagnostic& d = rig.diagnostics.front();
      throw std::invalid_argument("robot profile " + d.field + ": " + d.message);
    }
    require(std::isfinite(config.mouse_floor_gap_m) && config.mouse_floor_gap_m >= 0.0,
            "mouse_floor_gap_m must be finite and >= 0");
    mice.emplace(MouseSensorSimulator(rig.rig->spec, rig.rig->right, config.mouse_noise),
                 MouseSensorSimulator(rig.rig->spec, rig.rig->left, config.mouse_noise));
  }

  void readMice(const Pose2& before, TelemetrySample& sample) {
    if (!mice) {
      sample.mouse.reset();
      return;
    }
    const BodyIncrement increment = incrementBetween(before, true_pose);
    const double gap = config.mouse_floor_gap_m;
    const MouseCounts right = mice->first.sample(increment, config.dt_s, gap, mouse_rng);
    const MouseCounts left = mice->second.sample(increment, config.dt_s, gap, mouse_rng);
    // Cumulative, as a host accumulates the chips' reports: a consumer that sees only some
    // samples (the GUI shows one per frame) still gets every count.
    mouse_total.right.dx += right.dx;
    mouse_total.right.dy += right.dy;
    mouse_total.right.status = right.status;
    mouse_total.left.dx += left.dx;
    mouse_total.left.dy += left.dy;
    mouse_total.left.status = left.status;
    sample.mouse = mouse_total;
  }

  void step(TelemetrySample& sample) {
    const Pose2 before = true_pose;
    moveMovers(time());
    move();
    ++steps;
    const double now = time();
    const double c = std::cos(true_pose.theta), s = std::sin(true_pose.theta);
    sample.sonar.clear();
    fireSonars(now, c, s, sample.sonar);
    updateProximity(now, c, s);
    updateBumpers();

    sample.time_s = now;
    sample.odometry_pose = odom_pose;
    sample.true_pose = true_pose;
    sample.measured_velocity = {measured_ds / config.dt_s, measured_dtheta / config.dt_s};
    sample.left_ticks = left_ticks;
    sample.right_ticks = right_ticks;
    sample.bumpers = bumper_bits;
    sample.drive_stalled = stalled_s >= kStallAfter_s;
    sample.proximity_m.resize(proximity.size());
    for (std::size_t i = 0; i < proximity.size(); ++i)
      sample.proximity_m[i] = proximity[i].value_m;
    if (gyro)
      sample.gyro = gyro->read(true_velocity.angular_radps, now, config.dt_s);
    else
      sample.gyro.reset();
    readMice(before, sample);
    if (casters)
      sample.casters = casters->encoders();
    else
      sample.casters.reset();
  }
};

Simulator::Simulator(WorldMap map, RobotProfile profile, SimConfig config)
    : impl_(std::make_unique<Impl>(std::move(map), std::move(profile), config)) {}
Simulator::~Simulator() = default;
Simulator::Simulator(Simulator&&) noexcept = default;
Simulator& Simulator::operator=(Simulator&&) noexcept = default;

void Simulator::setCommand(const VelocityCommand& command) {
  if (!std::isfinite(command.linear_mps) || !std::isfinite(command.angular_radps))
    throw std::invalid_argument("Simulator::setCommand: non-finite velocity");
  impl_->command = command;
}

void Simulator::halt() {
  impl_->command = {};
  impl_->v_mps = impl_->omega_radps = 0.0;
}

TelemetrySample Simulator::step() {
  TelemetrySample sample;
  impl_->step(sample);
  return sample;
}

void Simulator::step(TelemetrySample& sample) {
  impl_->step(sample);
}

void Simulator::setMap(WorldMap map) {
  impl_->map = std::move(map);
  impl_->buildWorld();
}

void Simulator::resetPose(const Pose2& pose) {
  if (!std::isfinite(pose.x) || !std::isfinite(pose.y) || !std::isfinite(pose.theta))
    throw std::invalid_argument("Simulator::resetPose: non-finite pose");
  const Pose2 wrapped{pose.x, pose.y, wrapAngle(pose.theta)};
  impl_->true_pose = impl_->odom_pose = wrapped;
  impl_->command = {};
  impl_->v_mps = impl_->omega_radps = 0.0;
  impl_->true_velocity = {};
  impl_->clearance_fresh = false;
  impl_->clearance = 0.0;
}

double Simulator::time_s() const {
  return impl_->time();
}
const Pose2& Simulator::truePose() const {
  return impl_->true_pose;
}
const Pose2& Simulator::odometryPose() const {
  return impl_->odom_pose;
}
const WorldMap& Simulator::map() const {
  return impl_->map;
}
const RobotProfile& Simulator::profile() const {
  return impl_->profile;
}
const SimConfig& Simulator::config() const {
  return impl_->config;
}
const VelocityCommand& Simulator::command() const {
  return impl_->command;
}
VelocityCommand Simulator::trueVelocity() const {
  return impl_->true_velocity;
}
std::uint32_t Simulator::bumpers() const {
  return impl_->bumper_bits;
}
std::int64_t Simulator::stepCount() const {
  return impl_->steps;
}
const std::vector<std::vector<Vec2>>& Simulator::movingObstaclePolygons() const {
  return impl_->mover_polygons;
}

const SimWorld& Simulator::world() const {
  return *impl_->world;
}

}  // namespace irgs
