#pragma once
// Command line of irgs-sim, parsed into a plain value.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/geometry/types.hpp"

namespace irgs::app {

struct SimOptions {
  std::filesystem::path map;
  std::filesystem::path robot;  // empty: the bundled thesis robot
  std::optional<Pose2> start;   // theta given in degrees on the command line
  std::filesystem::path script;
  std::uint64_t seed = 1;
  std::optional<double> duration_s;  // default: the script's length, or 60 s without a script
  std::filesystem::path out;
  double grid_resolution_m = 0.01;
  bool ideal = false;  // no odometry error and no sensor noise
  bool quiet = false;
};

struct SimOptionsResult {
  std::optional<SimOptions> options;
  bool help = false;
  std::string error;  // set when options is empty and help is false
};

SimOptionsResult parseSimOptions(const std::vector<std::string>& args);
std::string simUsage();

}  // namespace irgs::app
