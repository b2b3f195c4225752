#pragma once
// The four position-revision routines of the ultrasonic map-building thesis (003_…, section
// 3.3, Figs. 3.8-3.11; digest 4.6) as small pure functions. Body frame: x forward, y left;
// angles CCW positive, radians. Distances are metres from the sonar's face.

#include <optional>

namespace irgs {

// Rounds angle_rad to the nearest multiple of quantum_rad (quantum 0 returns the angle).
double quantiseAngle(double angle_rad, double quantum_rad);

// (a) Turn in front of a wall: two forward-looking sonars at the same x, lateral baseline
// baseline_m apart (left one at +baseline/2), read left_m and right_m on the wall ahead. The
// wall through the two echo points gives, by the right-triangle construction, the turn that
// leaves the robot parallel to the wall with the wall on the chosen side. Quantised to
// quantum_rad, never zero (at least one quantum away from the wall). nullopt for a bad
// baseline or non-finite/negative readings.
// How far the wall ahead is from square to the heading (0: straight across), from the same two
// forward echoes; nullopt as frontWallTurn.
std::optional<double> frontWallSkew(double left_m, double right_m, double baseline_m);

std::optional<double> frontWallTurn(double left_m, double right_m, double baseline_m,
                                    bool wall_on_left, double quantum_rad);

// (c) Angle of a side wall relative to the heading from two side sonars on the same side,
// front one baseline_m ahead of the rear one, reading (centre-referenced perpendicular)
// distances front_m and rear_m. Positive when the wall turns CCW relative to the heading.
// wall_on_left selects the side (the sign of the lateral axis). nullopt for bad inputs.
std::optional<double> sideWallAngle(double front_m, double rear_m, double baseline_m,
                                    bool wall_on_left);

// (c) Restore parallel: the in-place turn (a multiple of quantum_rad) that cancels a wall angle
// of at least threshold_rad; nullopt while the robot is within the deadband (A003-4).
std::optional<double> parallelCorrection(double wall_angle_rad, double threshold_rad,
                                         double quantum_rad);

// (b) Turn with clearance around a convex corner: when the wall-side sonar mounted at
// sensor_x_m (body x) loses the wall that was side_range_m away, the corner lies about
// sensor_x_m - side_range_m * tan(half_beam_rad) ahead of the centre. The robot drives this far
// before turning 90 degrees toward the wall so that afterwards the corner is distance_m behind
// its side (parallel to the new face with no extra correction). Never negative.
double cornerClearance(double sensor_x_m, double side_range_m, double half_beam_rad,
                       double distance_m);

// (d) Keep within the valid distance: the heading offset (relative to the wall direction,
// toward the wall when positive) that brings a robot perpendicular distance_m from the wall
// back to target_m. Proportional with gain gain_rad_per_m, limited to max_offset_rad; once the
// wall is beyond valid_m the full max_offset_rad is used so the robot returns inside the range
// where its sonar data are trusted.
double distanceKeepingOffset(double distance_m, double target_m, double valid_m,
                             double gain_rad_per_m, double max_offset_rad);

}  // namespace irgs
