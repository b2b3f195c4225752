#pragma once
// Plain-text dumps of what a session showed, for comparing a live run with its replay
// (irgs --trajectory-out / --grid-out, tests/e2e/recording_replay_e2e_test.cpp).
//
//   trajectory CSV: "t_s,x_m,y_m,theta_rad" then one row per shown pose (session time, odometry
//                   pose, world frame)
//   grid CSV:       "resolution_m,<r>" then "col,row,log_odds" per observed cell

#include "core/geometry/types.hpp"
#include "core/mapping/occupancy_grid.hpp"

#include <string>
#include <vector>

namespace irgs::recording {

struct TrajectoryPoint {
  double t_s = 0.0;
  Pose2 pose;
};

// Both return an empty string on success, else why not.
std::string writeTrajectoryCsv(const std::vector<TrajectoryPoint>& points, const std::string& path);
std::string writeGridCsv(const OccupancyGrid& grid, const std::string& path);

}  // namespace irgs::recording
