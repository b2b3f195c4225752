#pragma once
// Which robot profile and map a re-run uses (docs/gui.md, "Re-run with parameters"). The
// profile decides how the bytes become samples (sonar indices) and where each sonar sits, so it
// must be the session's: an explicit file first, else the recording's meta "robot_file" when it
// still exists, else the bundled profile (resource_dirs/robots/*.json) whose name equals the
// meta "robot", else the fallback the caller has (the GUI's own profile) — with a warning. The
// map only feeds the stereo EKF's features: an explicit file, else the meta "map" when it
// exists, else none.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "app/recording/recording_format.hpp"
#include "core/robot/robot_profile.hpp"
#include "core/world/world_map.hpp"

namespace irgs::recording {

struct RerunInputs {
  std::optional<RobotProfile> profile;  // empty when error is set
  std::string profile_source;           // the file, or "fallback"
  WorldMap map;                         // empty when none was found
  std::string map_source;               // the file, empty for none
  std::vector<std::string> warnings;
  std::string error;
};

RerunInputs resolveRerunInputs(const Recording& recording, const std::string& robot_file,
                               const std::string& map_file,
                               const std::vector<std::filesystem::path>& resource_dirs,
                               const std::optional<RobotProfile>& fallback = std::nullopt);

}  // namespace irgs::recording
