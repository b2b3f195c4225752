#pragma once
// Turn and heading-hold control laws of the motion primitives and the host behaviours: on-the-spot
// turns to a heading and straight legs with heading hold, on the odometry pose, SI units.

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/geometry/types.hpp"
#include "core/robot/telemetry.hpp"

namespace irgs {

// turnRate's default floor: static friction never stalls the last degree.
inline constexpr double kTurnFloor_radps = 0.15;

// Angular velocity that turns the robot from heading_rad to target_rad: proportional with a
// floor (so static friction never stalls the last degree) and the rate limit. Never zero, so a
// caller that also waits for the robot to settle must not use it inside the tolerance (a
// sampled, delayed link then hunts across the target at the floor rate): use turnStep.
inline double turnRate(double heading_rad, double target_rad, double max_rate_radps,
                       double floor_radps = kTurnFloor_radps) {
  const double err = wrapAngle(target_rad - heading_rad);
  const double w = std::clamp(3.0 * err, -max_rate_radps, max_rate_radps);
  const double floor = std::min(floor_radps, max_rate_radps);
  return std::abs(w) < floor ? std::copysign(floor, err) : w;
}

// True once the heading is within tolerance of the target.
inline bool turnDone(double heading_rad, double target_rad, double tolerance_rad = degToRad(1.0)) {
  return std::abs(wrapAngle(target_rad - heading_rad)) <= tolerance_rad;
}

// What an on-the-spot turn remembers between steps: its target, the last heading error and
// whether the heading has crossed the target yet.
struct TurnProgress {
  double target_rad = std::numeric_limits<double>::quiet_NaN();
  double last_error_rad = 0.0;
  bool crossed = false;
};

// One step of an on-the-spot turn that ends at rest on the target heading.
struct TurnStep {
  double angular_radps = 0.0;  // the rate to command this step
  bool done = false;           // inside the tolerance and settled: the turn is over
};

// Settle threshold of turnStep: below this measured rate the robot counts as turned (on a
// 1 deg tolerance, what is left of the motion after the last command adds a fraction of it).
inline constexpr double kTurnSettledRate_radps = 0.1;
// turnStep's floor once the heading has crossed the target (3 deg/s): slow enough to stop
// inside a 1 deg tolerance with 0.5 s between a sample and its command taking effect.
inline constexpr double kTurnSettleFloor_radps = 0.05;

// Until the heading first crosses the target: turnRate (proportional, rate-limited, floored
// at 0.15 rad/s), also inside the tolerance, so the robot stops just past the target, not at
// the near edge of the tolerance (stepped every 10 ms, a turn ends within a fraction of a
// degree of it). After a crossing: zero inside the tolerance, so the robot brakes where it is,
// and outside it turnRate with the lower kTurnSettleFloor_radps, so an overshoot is taken back
// slowly enough to end inside the band. turnRate alone never commands zero: over a 10 Hz link with
// 0.1 s of delay every crossing overshoots the 1 deg tolerance at the floor rate, the robot
// reverses, overshoots again, and the turn only ends when a sample happens to catch a reversal
// inside the band (never, in the deterministic model of tests/core/behaviour/motion_test.cpp; 2-45
// s per turn with jitter). Done once inside the tolerance with |measured_rate_radps| below
// kTurnSettledRate_radps, so the next move does not start while the body still swings. A new
// target_rad starts a new turn.
inline TurnStep turnStep(TurnProgress& progress, double heading_rad, double target_rad,
                         double measured_rate_radps, double max_rate_radps,
                         double tolerance_rad = degToRad(1.0)) {
  const double err = wrapAngle(target_rad - heading_rad);
  if (!(progress.target_rad == target_rad)) {
    progress = {target_rad, err, false};
  } else if (std::abs(err) < 0.5 * kPi && std::abs(progress.last_error_rad) < 0.5 * kPi &&
             (err > 0.0) != (progress.last_error_rad > 0.0)) {
    progress.crossed = true;  // not a wrap at +-pi: the heading went through the target
  }
  progress.last_error_rad = err;
  const bool inside = std::abs(err) <= tolerance_rad;
  const bool settled = std::abs(measured_rate_radps) < kTurnSettledRate_radps;
  if (inside && progress.crossed)
    return {0.0, settled};
  const double floor = progress.crossed ? kTurnSettleFloor_radps : kTurnFloor_radps;
  return {turnRate(heading_rad, target_rad, max_rate_radps, floor), inside && settled};
}

// Heading hold for a straight leg: a proportional correction toward hold_rad.
inline VelocityCommand straightCommand(double heading_rad, double hold_rad, double speed_mps) {
  return {speed_mps, std::clamp(2.0 * wrapAngle(hold_rad - heading_rad), -0.5, 0.5)};
}

}  // namespace irgs
