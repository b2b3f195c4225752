#pragma once
// The IRGS JSON map format ("format": "irgs-map", "version": 1); see docs/map-format.md.
//
// Loading never half-loads: the map is present only when no diagnostic is an error. Every
// diagnostic names the file, the line and column, the field (a JSON pointer such as
// "/walls/3/points") and what is wrong. Unknown keys are kept in the `extra` members and written
// back on save (keys starting with "x-" are extensions and load silently; other unknown keys load
// with a warning, as they are often typos).

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/io/diagnostic.hpp"
#include "core/world/world_map.hpp"

namespace irgs {

inline constexpr std::string_view kMapFormatName = "irgs-map";

struct MapLoadResult {
  std::optional<WorldMap> map;  // empty whenever diagnostics hold an error
  std::vector<Diagnostic> diagnostics;
};

// Parses map JSON text. `source_name` names the file in diagnostics; a raster layer's source is
// resolved relative to `base_dir`. Obstacle polygons are stored counter-clockwise.
MapLoadResult parseMapJson(std::string_view text, const std::string& source_name,
                           const std::filesystem::path& base_dir);
MapLoadResult loadMapFile(const std::filesystem::path& path);

// Loads by extension: .json -> loadMapFile; .yaml/.yml -> a ROS map_server map wrapped by
// worldFromRaster (start pose with 0.25 m clearance; a warning when no cell offers it).
MapLoadResult loadAnyMap(const std::filesystem::path& path);

// Pretty, deterministic JSON (fixed key order, then unknown keys sorted; short arrays and flat
// objects on one line), ending in a newline. Throws std::invalid_argument for a non-finite
// number, naming its JSON pointer.
std::string serializeMap(const WorldMap& map);
// serializeMap + atomic write. A raster layer with resolved_path is referenced relative to the
// file's folder. Returns an error message on failure.
std::optional<std::string> saveMapFile(const WorldMap& map, const std::filesystem::path& path);

}  // namespace irgs
