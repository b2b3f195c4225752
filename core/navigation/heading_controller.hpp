#pragma once
// Path tracking on the differential drive (002_… 3.7, eqs. (9)-(14)) with the corrections of
// A002-3, A002-4 and A002-7:
//   alpha = atan2(y_m, x_m)          the move vector's angle from the forward x axis (replaces (9))
//   w     = k_theta * alpha          (10), positive = counter-clockwise = toward +y (left)
//   v_r   = v + w B / 2,  v_l = v - w B / 2      (14) with B the FULL wheel separation
//   w     = (v_r - v_l) / B,  v = (v_r + v_l) / 2   (12), (13)

#include "core/geometry/types.hpp"
#include "core/robot/telemetry.hpp"

namespace irgs {

struct HeadingControlParams {
  double k_theta = 1.6;  // 1/s (no paper value)
  double max_turn_rate_radps = 1.2;
  // The forward speed shrinks with the heading error, v = speed * max(0, cos alpha)^2, so a
  // move vector behind the robot turns it on the spot instead of driving away from the goal.
  double turn_in_place_rad = 1.4;  // beyond this |alpha| the robot only turns
};

struct WheelCommand {
  double left_mps = 0.0;
  double right_mps = 0.0;
};

// alpha of A002-7 (0 for a zero vector).
double moveVectorAngle(const Vec2& move_body);

// (v, w) that tracks `move_body` at up to `speed_mps` (eq. (10) and the speed rule above).
VelocityCommand trackMoveVector(const HeadingControlParams& params, const Vec2& move_body,
                                double speed_mps);

// Eq. (14) with B = full wheel separation (A002-4): the wheel speeds for (v, w).
WheelCommand wheelSpeedsFor(double v_mps, double w_radps, double wheel_separation_m);

// Eqs. (12)-(13): body velocity back from the wheel speeds.
VelocityCommand bodyVelocityFrom(const WheelCommand& wheels, double wheel_separation_m);

}  // namespace irgs
