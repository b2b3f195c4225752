#pragma once
// What irgs-rerun writes (docs/gui.md, "Re-run with parameters"), into one folder:
//   recorded_map.png / rerun_map.png     the grids (black occupied, white free, grey unknown)
//   recorded_map.yaml+.pgm / rerun_map.* the grids as ROS map_server maps
//   recorded_grid.csv / rerun_grid.csv   every observed cell's log-odds (irgs --grid-out format)
//   recorded_trajectory.csv / rerun_trajectory.csv
//       recording_t_s,robot_t_s,odom_x,odom_y,odom_theta,x,y,theta[,truth_x,truth_y,truth_theta]
//   metrics.json                         both parameter sets, what changed, decode counters and
//                                        the comparison (grid agreement, F1, pose and truth error)
// PNG needs Qt Gui (QImage); everything else is plain files.

#include <filesystem>
#include <string>

#include "app/recording/rerun_engine.hpp"

namespace irgs::recording {

// The metrics JSON text (also what the GUI's table shows, from the same numbers).
std::string rerunMetricsJson(const RerunResult& result, const std::string& recording_name);

// Writes every file above into `dir` (created). Returns an error message, empty on success.
std::string writeRerunOutputs(const RerunResult& result, const std::filesystem::path& dir,
                              const std::string& recording_name);

}  // namespace irgs::recording
