#pragma once
// Two-sensor optical-mouse odometry of paper 004 (digest 5.4): one floor sensor cannot see its
// own rotation, so two sensors a known distance D apart give the rotation and the displacement
// of the robot centre over each sampling interval, (4)-(15).
//
// Frames (A004-1): everything here is in the project's body frame, x forward, y left. Paper 004
// puts the sensors on its lateral x axis, right sensor at +D/2; here that is the body y axis,
// right sensor at (0, -D/2), left at (0, +D/2), and the paper's "sign(y_r - y_l)" (forward
// readings) becomes the sign of the forward difference. The pose integrated by (13)-(15) is the
// body pose (theta = forward heading), not the paper's lateral-axis angle (theta_004 + pi/2).
//
// The equations are written for any two mounts (the rig need not be symmetric, the sensors may
// be rotated): counts are first rotated into body axes; D = |p_left - p_right|; the centre
// displacement is that of the body origin, not of the sensors' midpoint. For the paper's rig
// (symmetric, unrotated) every step reduces to the printed equation.

#include <optional>
#include <string>
#include <vector>

#include "core/estimation/mouse_sensor.hpp"
#include "core/io/diagnostic.hpp"
#include "core/robot/robot_profile.hpp"

namespace irgs {

struct MouseRig {
  MouseSensorSpec spec;  // both sensors are the same part
  MouseMount right;      // paper 004: right sensor, +D/2 on its lateral axis
  MouseMount left;       // paper 004: left sensor ("t" in the OCR, A004-2)

  double separation_m() const { return (left.position() - right.position()).norm(); }
};

// The paper's rig: sensors on the body y axis, D apart, symmetric about the origin, unrotated.
MouseRig symmetricMouseRig(double separation_m, MouseSensorSpec spec = {});

// Throws std::invalid_argument for an invalid spec, non-finite mounts or D below 1 mm.
void validate(const MouseRig& rig);

// The rig of a robot profile with drive type "mouse_sensor" (resources/robots/*.json), from the
// drive's "mouse_sensors" object (kept by the profile reader in DriveGeometry::extra):
//   "mouse_sensors": { "counts_per_inch", "max_speed_mps", "max_lift_m", "frame_rate_hz"
//                      (optional, > 0, default MouseSensorSpec),
//                      "right": {"x_m", "y_m", "heading_deg"}, "left": {...} (required) }
struct MouseRigResult {
  std::optional<MouseRig> rig;          // present when there is no error
  std::vector<Diagnostic> diagnostics;  // field = JSON pointer into the profile file
};
MouseRigResult mouseRigFromProfile(const RobotProfile& profile);

enum class MouseMotionStatus {
  kOk,
  kSaturated,     // at least one sensor saturated: the increment is under-estimated
  kLostTracking,  // at least one sensor lifted off: no increment can be inferred (zero)
};
const char* toString(MouseMotionStatus status);

// The whole inference of one interval, every intermediate of (1)-(12) kept for display/tests.
struct TwoSensorMotion {
  MouseMotionStatus status = MouseMotionStatus::kOk;
  SensorMotion right;             // (1)-(3) of the right sensor, alpha in BODY axes
  SensorMotion left;              // (1)-(3) of the left sensor, alpha in BODY axes
  double gamma_rad = 0.0;         // angle between the two displacements, alpha_r - alpha_l (A004-2)
  double dtheta_rad = 0.0;        // (6)
  Vec2 right_end = Vec2::Zero();  // (7)/(8): right sensor after the interval, start body frame
  Vec2 left_end = Vec2::Zero();   // (9)/(10)
  Vec2 centre = Vec2::Zero();     // (11)/(12): body origin after the interval, start body frame
  // How far the two readings are from a rigid motion (m): the component of the relative
  // displacement along the baseline, which a rigid body cannot produce. Zero without noise.
  double rigidity_residual_m = 0.0;
};

// (4)-(12) from the two sensors' displacements in metres, each in its own sensor axes.
TwoSensorMotion inferTwoSensorMotion(const MouseRig& rig, const Vec2& right_m, const Vec2& left_m);
// The same from counts (metres = counts * 0.0254 / cpi); a lifted sensor gives kLostTracking.
TwoSensorMotion inferTwoSensorMotion(const MouseRig& rig, const MouseCounts& right,
                                     const MouseCounts& left);

// Dead reckoning with the two sensors: (13)-(15) after each interval's inference.
class MouseOdometry {
 public:
  // Throws std::invalid_argument for an invalid rig or a non-finite start pose.
  MouseOdometry(MouseRig rig, const Pose2& start);

  void reset(const Pose2& pose);
  // Integrates one interval; kLostTracking leaves the pose unchanged (returned as is).
  TwoSensorMotion update(const MouseCounts& right, const MouseCounts& left);

  const Pose2& pose() const { return pose_; }
  const MouseRig& rig() const { return rig_; }
  // Path length of the centre integrated so far (sum of chord lengths), metres.
  double distance_m() const { return distance_m_; }
  int lostIntervals() const { return lost_intervals_; }
  int saturatedIntervals() const { return saturated_intervals_; }

 private:
  MouseRig rig_;
  Pose2 pose_;
  double distance_m_ = 0.0;
  int lost_intervals_ = 0;
  int saturated_intervals_ = 0;
};

}  // namespace irgs
