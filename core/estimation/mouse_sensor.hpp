#pragma once
// The optical-mouse floor sensor of paper 004 (digest 5.2, 5.3): a 2-D motion sensor (PAN3101DB
// behind a laser "G-laser" lens) looking at the floor, reporting the displacement of the floor
// under it as (x, y) counts in its own axes, accumulated over a sampling interval.
//
// Frames (project convention, A004-1): the sensor frame is x forward, y left when the sensor is
// mounted unrotated (MouseMount::phi_rad = 0); paper 004 writes the sensor x axis lateral (right)
// and y forward. Counts report the motion of the SENSOR over the floor (a mouse moved forward
// reports +x), expressed in the sensor's own, rotating axes. Lengths in metres.
//
// Sensor model (paper values from Table 1 of 004; digest 5.2):
//   * resolution counts_per_inch (400 or 800 cpi): 1 count = 0.0254 m / cpi, sub-count motion is
//     kept by the chip and reported later (no bias from quantisation);
//   * maximum tracking speed (21 in/s = 0.5334 m/s): faster motion saturates — the reported
//     displacement is clipped to max_speed * dt along the true direction [A: the paper gives the
//     limit, not the behaviour beyond it];
//   * lift-off: with the floor more than 2 mm away the sensor sees nothing and reports no motion.

#include <cstdint>

#include "core/geometry/types.hpp"
#include "core/robot/mouse_counts.hpp"
#include "core/sim/random.hpp"

namespace irgs {

inline constexpr double kMetresPerInch = 0.0254;

struct MouseSensorSpec {
  double counts_per_inch = 800.0;                // [004 Table 1: 400/800 cpi]
  double max_speed_mps = 21.0 * kMetresPerInch;  // [004 Table 1: 21 in/s = 0.5334 m/s]
  double max_lift_m = 0.002;                     // [004 conclusion: unusable beyond a 2 mm gap]
  double frame_rate_hz = 3000.0;                 // [004 Table 1] (informative; not simulated)

  double metresPerCount() const { return kMetresPerInch / counts_per_inch; }
};

// Throws std::invalid_argument unless every field is finite and > 0.
void validate(const MouseSensorSpec& spec);

// Where a sensor sits on the robot: position of its optical centre in the body frame (x forward,
// y left) and the rotation of its x axis counter-clockwise from the body x axis.
struct MouseMount {
  double x_m = 0.0;
  double y_m = 0.0;
  double phi_rad = 0.0;

  Vec2 position() const { return {x_m, y_m}; }
};

// Single-sensor motion (1)-(3): direction alpha of the sensor's motion in its frame and the
// travelled (arc) length l, with x-bar = l cos(alpha), y-bar = l sin(alpha). Robust form
// (A004-5): alpha = atan2(y-bar, x-bar), l = hypot(x-bar, y-bar); alpha = 0 for no motion.
struct SensorMotion {
  double alpha_rad = 0.0;
  double length_m = 0.0;
};
SensorMotion sensorMotion(double x_bar_m, double y_bar_m);

// A rigid-body increment over one interval under a constant body twist: (dx, dy) = the twist's
// linear part times the interval (body frame at the START of the interval, metres), dtheta the
// rotation (rad). Not the chord: for a turn the chord is shorter than dx.
struct BodyIncrement {
  double dx_m = 0.0;
  double dy_m = 0.0;
  double dtheta_rad = 0.0;
};

// The pose reached from `start` by the constant-twist increment (exact arc).
Pose2 applyIncrement(const Pose2& start, const BodyIncrement& increment);
// The constant-twist increment that takes `from` to `to` (inverse of applyIncrement for
// |dtheta| < pi).
BodyIncrement incrementBetween(const Pose2& from, const Pose2& to);

// What a sensor at `mount` accumulates (metres, sensor axes) while the body moves by the
// constant-twist increment: the body-frame velocity of a body-fixed point is constant, so the
// counts are (dx - dtheta y_p, dy + dtheta x_p) rotated into the sensor axes.
Vec2 sensorDisplacement(const MouseMount& mount, const BodyIncrement& increment);

// Errors of a simulated sensor beyond quantisation, saturation and lift-off. [A] paper 004 gives
// none; the counts-to-metres calibration per surface is named there as not studied.
struct MouseNoise {
  double scale_error = 0.0;      // systematic: reported / true displacement - 1 (the surface)
  double relative_stddev = 0.0;  // random, per axis, relative to the interval's displacement
  double stddev_m = 0.0;         // random, per axis, per interval (floor texture)
};

// Throws std::invalid_argument for non-finite values, negative stddevs or scale_error <= -1.
void validate(const MouseNoise& noise);

// Turns true motion into counts for one sensor. Deterministic for a given SimRandom stream.
class MouseSensorSimulator {
 public:
  // Throws std::invalid_argument for an invalid spec, noise or non-finite mount.
  MouseSensorSimulator(MouseSensorSpec spec, MouseMount mount, MouseNoise noise = {});

  // Counts of one interval of dt_s seconds during which the body moved by `increment` with the
  // floor `floor_gap_m` below the sensor. Throws std::invalid_argument for non-finite input,
  // dt_s <= 0 or a displacement beyond 1e15 counts. Draws exactly two gaussians per call (so
  // streams stay aligned whatever happens).
  MouseCounts sample(const BodyIncrement& increment, double dt_s, double floor_gap_m,
                     SimRandom& rng);

  const MouseSensorSpec& spec() const { return spec_; }
  const MouseMount& mount() const { return mount_; }
  const MouseNoise& noise() const { return noise_; }

 private:
  MouseSensorSpec spec_;
  MouseMount mount_;
  MouseNoise noise_;
  Vec2 remainder_counts_ = Vec2::Zero();  // sub-count motion not reported yet
};

}  // namespace irgs
