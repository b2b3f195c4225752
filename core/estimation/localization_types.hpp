#pragma once
// Fixed-size state types of the paper-000 localization EKF: the robot pose U = (x, y, Phi)
// (20) in world metres/radians, with named indices.

#include <Eigen/Core>

#include "core/geometry/types.hpp"

namespace irgs {

inline constexpr int kLocX = 0;
inline constexpr int kLocY = 1;
inline constexpr int kLocPhi = 2;
inline constexpr int kLocStateSize = 3;

using LocState = Eigen::Matrix<double, kLocStateSize, 1>;
using LocCov = Eigen::Matrix<double, kLocStateSize, kLocStateSize>;
using LocRow = Eigen::Matrix<double, 1, kLocStateSize>;  // scalar measurement Jacobian

inline LocState toLocState(const Pose2& pose) {
  return {pose.x, pose.y, pose.theta};
}
inline Pose2 toPose(const LocState& x) {
  return {x(kLocX), x(kLocY), x(kLocPhi)};
}

// Mounting pose of a sensor's transmitter in the robot frame: (x'_T, y'_T) (x forward, y left)
// and boresight phi'_T counter-clockwise from the robot's x axis.
struct SensorMount {
  double x_m = 0.0;
  double y_m = 0.0;
  double phi_rad = 0.0;
};

}  // namespace irgs
