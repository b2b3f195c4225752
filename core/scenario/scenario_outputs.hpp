#pragma once
// Writes what a headless scenario produced, each file atomically:
//   grid.pgm + grid.yaml  the sonar grid as a ROS map_server map (trinary)
//   grid.png              the grid as a picture with the true (blue) and odometry (orange) paths
//   metrics.json          distance, final true and odometry pose, odometry error, explored area
//   trajectory.csv        time, true pose, odometry pose, command, bumpers per row
// Outputs depend only on the result, so the same seed gives byte-identical files.

#include <filesystem>
#include <string>
#include <vector>

#include "core/scenario/scenario_runner.hpp"

namespace irgs {

struct ScenarioRunInfo {
  std::string map_source;
  std::string robot_name;
  std::uint64_t seed = 0;
};

struct WriteOutputsResult {
  std::vector<std::filesystem::path> written;
  std::string error;  // empty on success
};

WriteOutputsResult writeScenarioOutputs(const ScenarioResult& result, const ScenarioRunInfo& info,
                                        const std::filesystem::path& out_dir);

// The individual documents, for tests and other writers.
std::string metricsJson(const ScenarioMetrics& metrics, const ScenarioRunInfo& info);
std::string trajectoryCsv(const std::vector<TrajectoryRow>& rows);
// RGB picture of the grid (row 0 = top) with both paths drawn on it.
std::string gridPicturePng(const OccupancyGrid& grid, const std::vector<TrajectoryRow>& rows);

}  // namespace irgs
