#pragma once
// The camera's tilt servo of 002_… (A002-5): the camera-to-ceiling angle theta is 90 deg when
// the tracked landmark is overhead and 35 deg when it is far, linear in the landmark's
// horizontal distance between two configurable distances. The state machine of 002_… speaks of
// the tilt from vertical, beta = 90 deg - theta (0 when the marker is overhead).

namespace irgs {

struct TiltLaw {
  double min_tilt_rad = 0.6108652381980153;  // 35 deg: landmark at far_m or beyond
  double max_tilt_rad = 1.5707963267948966;  // 90 deg: landmark at near_m or closer
  double near_m = 0.3;
  double far_m = 4.0;

  // theta for a landmark `distance_m` away (horizontal, from the camera). Clamped outside
  // [near_m, far_m]. Throws std::invalid_argument unless near_m < far_m.
  double tiltFor(double distance_m) const;
  // The distance at which tiltFor gives `tilt_rad` (clamped to [near_m, far_m]).
  double distanceFor(double tilt_rad) const;
};

// Tilt from vertical, beta = 90 deg - theta (A002-5).
inline double tiltFromVertical(double tilt_rad) {
  return 1.5707963267948966 - tilt_rad;
}

// A slew-limited servo following a commanded tilt; starts at `initial_rad`.
class TiltServo {
 public:
  TiltServo(double initial_rad, double max_rate_radps);
  // Moves towards `command_rad` for `dt_s` at no more than the maximum rate; returns the new
  // angle.
  double step(double command_rad, double dt_s);
  double angleRad() const { return angle_rad_; }

 private:
  double angle_rad_;
  double max_rate_radps_;
};

}  // namespace irgs
