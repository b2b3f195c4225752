#include "core/motion/position_revision.hpp"

#include <algorithm>
#include <cmath>

#include "core/geometry/types.hpp"

namespace irgs {

double quantiseAngle(double angle_rad, double quantum_rad) {
  if (!(quantum_rad > 0.0) || !std::isfinite(angle_rad))
    return angle_rad;
  return std::round(angle_rad / quantum_rad) * quantum_rad;
}

std::optional<double> frontWallSkew(double left_m, double right_m, double baseline_m) {
  if (!(baseline_m > 0.0) || !std::isfinite(left_m) || !std::isfinite(right_m) || left_m < 0.0 ||
      right_m < 0.0)
    return std::nullopt;
  return std::atan2(right_m - left_m, baseline_m);
}

std::optional<double> frontWallTurn(double left_m, double right_m, double baseline_m,
                                    bool wall_on_left, double quantum_rad) {
  if (!(baseline_m > 0.0) || !std::isfinite(left_m) || !std::isfinite(right_m) || left_m < 0.0 ||
      right_m < 0.0)
    return std::nullopt;
  // Echo points (left_m, +b/2) and (right_m, -b/2): the wall runs from the left point to the
  // right one along (right - left, -b). With the wall kept on the left the robot must head
  // along that vector; with the wall on the right, along its opposite.
  const double s = wall_on_left ? 1.0 : -1.0;
  double turn = std::atan2(-s * baseline_m, s * (right_m - left_m));
  turn = quantiseAngle(turn, quantum_rad);
  if (quantum_rad > 0.0 && std::abs(turn) < 0.5 * quantum_rad)
    turn = -s * quantum_rad;  // a wall ahead always asks for a turn away from it
  return wrapAngle(turn);
}

std::optional<double> sideWallAngle(double front_m, double rear_m, double baseline_m,
                                    bool wall_on_left) {
  if (!(baseline_m > 0.0) || !std::isfinite(front_m) || !std::isfinite(rear_m))
    return std::nullopt;
  // Wall points (bx, s*front) and (0, s*rear): the wall direction from rear to front.
  const double s = wall_on_left ? 1.0 : -1.0;
  return std::atan2(s * (front_m - rear_m), baseline_m);
}

std::optional<double> parallelCorrection(double wall_angle_rad, double threshold_rad,
                                         double quantum_rad) {
  if (!std::isfinite(wall_angle_rad) || std::abs(wall_angle_rad) < threshold_rad)
    return std::nullopt;
  const double turn = quantiseAngle(wall_angle_rad, quantum_rad);
  if (turn == 0.0)
    return std::nullopt;
  return turn;
}

double cornerClearance(double sensor_x_m, double side_range_m, double half_beam_rad,
                       double distance_m) {
  const double corner_x = sensor_x_m - std::max(0.0, side_range_m) * std::tan(half_beam_rad);
  return std::max(0.0, corner_x + distance_m);
}

double distanceKeepingOffset(double distance_m, double target_m, double valid_m,
                             double gain_rad_per_m, double max_offset_rad) {
  if (!std::isfinite(distance_m) || distance_m > valid_m)
    return max_offset_rad;
  return std::clamp(gain_rad_per_m * (distance_m - target_m), -max_offset_rad, max_offset_rad);
}

}  // namespace irgs
