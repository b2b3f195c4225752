#pragma once
// The tilt law of the ceiling camera (002_… 3.4, A002-5), kept in this one place.
//
// theta is the angle between the camera's optical axis and the ceiling plane: 35 deg when the
// landmark is far (the camera looks ahead), 90 deg when it is overhead (the camera looks straight
// up), linear in the landmark's horizontal distance between two configurable distances. The
// state machine of Fig. 18 speaks of the angle "reduced to 0" as the marker comes overhead: that
// is beta = 90 deg - theta, the tilt from vertical (A002-5).
//
// NOTE: the simulated camera of core/camera (vision helper) has its own servo model; when both
// are merged this law should be the one the servo is driven with.

namespace irgs {

struct CameraTiltLaw {
  double far_tilt_rad = 0.6108652381980153;   // 35 deg
  double near_tilt_rad = 1.5707963267948966;  // 90 deg
  double far_distance_m = 3.0;                // at or beyond: far_tilt_rad
  double near_distance_m = 0.3;               // at or within: near_tilt_rad
};

// theta for a landmark `distance_m` away horizontally (clamped to the law's two ends).
double tiltForDistance(const CameraTiltLaw& law, double distance_m);

// beta = 90 deg - theta: 0 when the camera looks straight up (A002-5).
double tiltFromVertical(double tilt_rad);

// 0 at the far tilt, 1 at the near tilt (clamped): how far the camera has risen, for slowing
// down as the robot closes in on a marker (Fig. 20).
double tiltRise(const CameraTiltLaw& law, double tilt_rad);

}  // namespace irgs
