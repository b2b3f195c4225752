#pragma once
// Differences between two trajectories of the same run (a recorded run and its re-run with
// changed parameters, or a run and the simulator's ground truth): position and heading
// differences at the first trajectory's times, the second interpolated there (linear in
// position, shortest arc in heading). Times are seconds on one clock (the recording's).

#include <cstddef>
#include <vector>

#include "core/geometry/types.hpp"

namespace irgs {

struct TimedPose {
  double t_s = 0.0;
  Pose2 pose;
};

struct TrajectoryDifference {
  std::size_t compared = 0;  // poses of `a` inside b's time span
  double rms_position_m = 0.0;
  double max_position_m = 0.0;
  double rms_heading_rad = 0.0;
  double max_heading_rad = 0.0;   // |wrapped heading difference|
  double final_position_m = 0.0;  // at the last compared pose
  double final_heading_rad = 0.0;
};

// `b` at time t_s, linear between its neighbours; false when t_s is outside b's time span or b is
// empty (no extrapolation). Trajectories must be sorted by time (ties allowed).
bool interpolatePose(const std::vector<TimedPose>& b, double t_s, Pose2& out);

// a - b at each time of `a` within b's span. Poses with non-finite values are skipped.
TrajectoryDifference compareTrajectories(const std::vector<TimedPose>& a,
                                         const std::vector<TimedPose>& b);

}  // namespace irgs
