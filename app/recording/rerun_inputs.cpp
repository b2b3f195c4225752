#include "app/recording/rerun_inputs.hpp"

#include <system_error>

#include "core/robot/robot_profile_file.hpp"
#include "core/world/map_file.hpp"

namespace irgs::recording {
namespace {

namespace fs = std::filesystem;

std::string firstError(const std::vector<Diagnostic>& diagnostics) {
  for (const Diagnostic& d : diagnostics) {
    if (d.severity == Severity::kError)
      return d.toString();
  }
  return "unreadable";
}

std::string metaValue(const Recording& recording, const std::string& key) {
  const auto it = recording.meta.find(key);
  return it == recording.meta.end() ? std::string() : it->second;
}

bool isFile(const fs::path& path) {
  std::error_code ec;
  return !path.empty() && fs::is_regular_file(path, ec);
}

}  // namespace

RerunInputs resolveRerunInputs(const Recording& recording, const std::string& robot_file,
                               const std::string& map_file,
                               const std::vector<fs::path>& resource_dirs,
                               const std::optional<RobotProfile>& fallback) {
  RerunInputs in;
  const std::string recorded_name = metaValue(recording, "robot");
  auto load = [&in](const fs::path& path) -> bool {
    RobotProfileResult r = loadRobotProfileFile(path);
    if (!r.profile) {
      in.warnings.push_back("robot profile " + path.string() + ": " + firstError(r.diagnostics));
      return false;
    }
    in.profile = std::move(*r.profile);
    in.profile_source = path.string();
    return true;
  };
  if (!robot_file.empty()) {
    if (!load(robot_file)) {
      in.error = in.warnings.back();
      return in;
    }
  }
  if (!in.profile) {
    const std::string recorded_file = metaValue(recording, "robot_file");
    if (isFile(recorded_file))
      load(recorded_file);  // a profile that no longer loads falls through, with a warning
  }
  if (!in.profile) {
    for (const fs::path& dir : resource_dirs) {
      std::error_code ec;
      if (in.profile || !fs::is_directory(dir / "robots", ec))
        continue;
      for (const fs::directory_entry& entry : fs::directory_iterator(dir / "robots", ec)) {
        if (entry.path().extension() != ".json")
          continue;
        RobotProfileResult r = loadRobotProfileFile(entry.path());
        if (r.profile && !recorded_name.empty() && r.profile->name == recorded_name) {
          in.profile = std::move(*r.profile);
          in.profile_source = entry.path().string();
          break;
        }
      }
    }
    if (!in.profile && fallback) {
      in.profile = *fallback;
      in.profile_source = "fallback";
      in.warnings.push_back("no robot profile named '" + recorded_name +
                            "' found: using the current profile '" + fallback->name + "'");
    }
    if (!in.profile) {
      in.error = "no robot profile named '" + recorded_name +
                 "' (the recording's robot) found: give one with --robot FILE";
      return in;
    }
  }
  if (!recorded_name.empty() && in.profile->name != recorded_name)
    in.warnings.push_back("the recording was made with robot '" + recorded_name +
                          "', the re-run uses '" + in.profile->name + "'");

  const fs::path map_path =
      !map_file.empty() ? fs::path(map_file) : fs::path(metaValue(recording, "map"));
  if (isFile(map_path)) {
    MapLoadResult m = loadAnyMap(map_path);
    if (m.map) {
      in.map = std::move(*m.map);
      in.map_source = map_path.string();
    } else {
      in.warnings.push_back("map " + map_path.string() + ": " + firstError(m.diagnostics));
    }
  } else if (!map_file.empty()) {
    in.warnings.push_back("map " + map_file + " does not exist");
  }
  return in;
}

}  // namespace irgs::recording
