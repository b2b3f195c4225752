#pragma once
// ROS map_server maps: a YAML metadata file beside a PGM image (https://wiki.ros.org/map_server,
// nav2_map_server). Import gives a RasterMap with nav_msgs/OccupancyGrid values (-1 unknown,
// 0 free .. 100 occupied); export writes PGM + YAML that map_server (and this importer) read back
// to the same cells.
//
// Pixel rules (nav2_map_server map_io, which these follow): shade = pixel / 255;
// occ = negate ? shade : 1 - shade.
//   trinary: occ > occupied_thresh -> 100, occ < free_thresh -> 0, otherwise -1.
//   scale:   as trinary, but between the thresholds rint(100 (occ - free) / (occupied - free)).
//   raw:     pixel 0..100 is the value itself, anything else -1 (negate has no effect).
// Image row 0 is the top of the map (largest y); RasterMap row 0 is the bottom.

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/io/diagnostic.hpp"
#include "core/io/pgm.hpp"
#include "core/world/raster_map.hpp"
#include "core/world/raster_world.hpp"

namespace irgs {

enum class RosMapMode { kTrinary, kScale, kRaw };

// The YAML keys as read (or to be written).
struct RosMapMetadata {
  std::string image;  // as written in the YAML (relative to the YAML's folder unless absolute)
  double resolution_m = 0.05;
  Pose2 origin;  // lower-left corner of the map; yaw is kept but not applied
  bool negate = false;
  double occupied_thresh = 0.65;
  double free_thresh = 0.196;
  RosMapMode mode = RosMapMode::kTrinary;
};

struct RosMapLoadResult {
  std::optional<RasterMap> raster;  // empty whenever diagnostics hold an error
  RosMapMetadata metadata;          // what could be read, also on error
  std::vector<Diagnostic> diagnostics;
};

// Loads a map YAML and the image it names. Diagnostics name the YAML file, the line and column,
// and the key (field) for YAML syntax errors and missing or invalid keys; image problems name
// the image file.
RosMapLoadResult loadRosMap(const std::filesystem::path& yaml_path);
// Same from YAML text already in memory; the image is looked up relative to `base_dir`.
RosMapLoadResult parseRosMap(std::string_view yaml_text, const std::string& source_name,
                             const std::filesystem::path& base_dir);

// Applies the pixel rules above to an image (row 0 = top) with the metadata's thresholds,
// resolution and origin.
RasterMap rasterFromImage(const GrayImage& image, const RosMapMetadata& metadata);

struct RosMapSaveOptions {
  RosMapMode mode = RosMapMode::kTrinary;
  bool negate = false;  // write inverted pixels and `negate: 1` (not for raw)
  double occupied_thresh = 0.65;
  double free_thresh = 0.196;
};

// The image map_server would need to reproduce `raster` under `options` (row 0 = top).
//   trinary: value <= rint(100 free_thresh) -> 254, >= rint(100 occupied_thresh) -> 0, other and
//            unknown -> 205 when 205 reads back as unknown under the thresholds, otherwise the
//            grey halfway between them.
//   scale:   the inverse of the import rule, so 0..100 read back unchanged whenever
//            occupied_thresh - free_thresh >= 0.4; unknown cannot be stored (PGM has no alpha)
//            and is written like trinary's unknown grey.
//   raw:     value 0..100 as the pixel, unknown -> 255.
// Throws std::invalid_argument for an empty raster or a cell count that does not match.
GrayImage imageFromRaster(const RasterMap& raster, const RosMapSaveOptions& options);

// Writes `<yaml stem>.pgm` beside `yaml_path` and then the YAML, each atomically. Returns an
// error message on failure (also for thresholds outside 0 < free < occupied < 1, a bad
// resolution or a non-finite origin).
std::optional<std::string> saveRosMap(const RasterMap& raster,
                                      const std::filesystem::path& yaml_path,
                                      const RosMapSaveOptions& options = {});

std::string_view toString(RosMapMode mode);

}  // namespace irgs
