#pragma once
// The three-caster steer/drive robot of paper 000 in simulation (digest 1.4): the body moves
// with the commanded twist; each caster's drive wheel and steering axis follow (26) and the six
// encoders count what they did, with the wheels' own errors. Used by Simulator for profiles
// with drive type "three_caster".
//
// Model, per dead-reckoning period (1 ms by default, the period of 000), under a constant body
// twist W:
// * true increments DeltaTheta = G(phi) W dt from (26) with the NOMINAL geometry, except that a
//   caster whose true radius is larger turns less for the same path (drive row / radius_scale);
// * the steering follows row 2 of (26) (a trailing caster swivels into the direction of travel;
//   turning on the spot swings it round);
// * the encoders count the true increments with random slip on the drive (relative, it
//   accumulates) and read the steering angle off by a random backlash (it does not), quantised
//   as cumulative counts
//   (DriveGeometry::ticksPerWheelRad() per radian, floor as for the wheel encoders);
// * the robot's own dead reckoning integrates each period's count differences with the
//   least-squares J+ (33) at the period's mid steering (what the paper's robot does at 1 ms),
//   and its residual ||e|| (35) is summed into the encoders' residual_sum_rad (with
//   residual_periods), as the robot reports it.
//
// Errors come from the profile's drive/three_caster/simulated_errors (see
// casterErrorsFromProfile) unless SimConfig overrides them.

#include <array>
#include <optional>
#include <vector>

#include "core/estimation/caster_odometry.hpp"
#include "core/geometry/types.hpp"
#include "core/io/diagnostic.hpp"
#include "core/robot/caster_encoders.hpp"
#include "core/robot/robot_profile.hpp"
#include "core/sim/random.hpp"

namespace irgs {

struct CasterErrorModel {
  std::array<double, 3> radius_scale{1.0, 1.0, 1.0};  // true wheel radius / nominal, per caster
  double drive_slip_stddev = 0.0;             // relative, per period, on each drive increment
  double steering_backlash_stddev_rad = 0.0;  // per reading, on each steering angle
};

// Throws std::invalid_argument unless the scales are finite and > 0 and the stddevs finite >= 0.
void validate(const CasterErrorModel& errors);

struct CasterErrorResult {
  std::optional<CasterErrorModel> errors;  // present when there is no error
  std::vector<Diagnostic> diagnostics;     // field = JSON pointer into the profile file
};

// Reads the optional object
//   "drive": {"three_caster": {"simulated_errors": {"radius_scale": [s1, s2, s3],
//             "drive_slip_stddev": s, "steering_backlash_stddev_rad": b}}}
// Every key is optional (missing = no error of that kind); no object = an error-free robot.
CasterErrorResult casterErrorsFromProfile(const RobotProfile& profile);

class CasterDriveSimulator {
 public:
  // Throws std::invalid_argument for invalid geometry/errors, ticks_per_rad <= 0 or
  // period_s <= 0.
  CasterDriveSimulator(const CasterDriveGeometry& nominal, const CasterErrorModel& errors,
                       double ticks_per_rad, double period_s = 0.001);

  // Moves the casters for dt_s under the constant body twist (V_ox, V_oy, Omega), in periods of
  // at most period_s, and integrates the robot's own J+ dead reckoning into `odometry`.
  void advance(const BodyTwist& twist, double dt_s, Pose2& odometry, SimRandom& rng);

  const CasterEncoders& encoders() const { return encoders_; }
  // The true steering angles phi_i (rad, wrapped).
  const std::array<double, 3>& steering() const { return steering_; }
  const CasterDriveGeometry& geometry() const { return nominal_; }
  double ticksPerRad() const { return ticks_per_rad_; }
  double period_s() const { return period_s_; }

 private:
  void period(const BodyTwist& twist, double h, Pose2& odometry, SimRandom& rng);

  CasterDriveGeometry nominal_;
  CasterErrorModel errors_;
  double ticks_per_rad_;
  double period_s_;
  std::array<double, 3> steering_{};            // true
  std::array<double, 3> drive_counted_{};       // what the encoders counted (rad, unquantised)
  std::array<double, 3> steering_unwrapped_{};  // true, not wrapped (the encoder's view)
  std::array<double, 3> steering_counted_{};    // true + backlash noise of this reading
  CasterEncoders encoders_;
};

}  // namespace irgs
