// Loading by path: an IRGS map file, or a ROS map_server map wrapped as a WorldMap. Parsing and
// writing live in map_file_reader.cpp and map_file_writer.cpp.
#include "core/world/map_file.hpp"

#include <algorithm>
#include <cctype>

#include "core/io/atomic_file.hpp"
#include "core/world/map_file_internal.hpp"
#include "core/world/raster_world.hpp"
#include "core/world/ros_map.hpp"

namespace irgs {
namespace {

namespace fs = std::filesystem;
using map_file_internal::quote;

constexpr double kStartClearance_m = 0.25;

}  // namespace

MapLoadResult loadMapFile(const fs::path& path) {
  const ReadFileResult file = readFile(path);
  if (!file.ok()) {
    MapLoadResult result;
    result.diagnostics.push_back({Severity::kError, path.string(), 0, 0, {}, file.error});
    return result;
  }
  return parseMapJson(file.bytes, path.string(), path.parent_path());
}

MapLoadResult loadAnyMap(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".json")
    return loadMapFile(path);
  MapLoadResult result;
  if (ext != ".yaml" && ext != ".yml") {
    result.diagnostics.push_back({Severity::kError,
                                  path.string(),
                                  0,
                                  0,
                                  {},
                                  "unknown map file type " +
                                      (ext.empty() ? std::string("(no extension)") : quote(ext)) +
                                      ": expected an IRGS map (.json) or a ROS map (.yaml)"});
    return result;
  }
  RosMapLoadResult ros = loadRosMap(path);
  result.diagnostics = std::move(ros.diagnostics);
  if (!ros.raster)
    return result;
  StartPoseSearch search;
  WorldMap world =
      worldFromRaster(std::move(*ros.raster), path.filename().string(), kStartClearance_m, &search);
  std::error_code ec;
  const fs::path absolute = fs::absolute(path, ec);
  world.raster->resolved_path = ec ? path.string() : absolute.lexically_normal().string();
  if (!search.found) {
    result.diagnostics.push_back(
        {Severity::kWarning,
         path.string(),
         0,
         0,
         {},
         "no free cell is at least 0.25 m from occupied or unknown cells; the start pose is the "
         "most open free cell found (clearance " +
             std::to_string(search.clearance_m) + " m)"});
  }
  result.map = std::move(world);
  return result;
}

}  // namespace irgs
