#pragma once
// Export of a built occupancy grid as a fixed raster (RasterMap) and as a ROS map_server map
// (PGM + YAML). Used by "save built map" in the GUI, irgs-sim and the hybrid map export.
//
// The raster is trinary (nav_msgs/OccupancyGrid values): a cell whose occupancy probability
// p = 1 / (1 + exp(-log_odds)) is above occupied_probability is 100, below free_probability is
// 0, anything else (including never-observed cells) is -1. The defaults are map_server's
// occupied_thresh / free_thresh, so the PGM written with the same thresholds reads back to the
// same cells.

#include <filesystem>
#include <optional>
#include <string>

#include "core/mapping/occupancy_grid.hpp"
#include "core/world/raster_map.hpp"

namespace irgs {

struct GridExportThresholds {
  double occupied_probability = 0.65;  // p > this -> occupied (100)
  double free_probability = 0.196;     // p < this -> free (0)
  // Cells of padding (unknown) added around the observed bounding box, so a map viewer shows
  // the outermost walls with a border. Must be >= 0.
  int padding_cells = 0;
};

// What is wrong with the thresholds (not 0 < free < occupied < 1, non-finite, negative padding),
// or nothing when they are usable.
std::optional<std::string> gridExportThresholdsError(const GridExportThresholds& thresholds);

// The observed part of `grid` (plus padding) as a trinary raster at the grid's resolution. Cell
// (0, 0) of the raster is the grid's lowest observed cell (minus padding); origin yaw is 0. An
// unobserved grid gives an empty raster (width = height = 0) with the grid's resolution.
// Throws std::invalid_argument for thresholds that gridExportThresholdsError rejects and when
// the observed area (plus padding) exceeds kMaxRasterCells.
inline constexpr long long kMaxRasterCells = 1LL << 30;  // 1 GiB of cells (~327 m square at 1 cm)
RasterMap rasterFromGrid(const OccupancyGrid& grid, const GridExportThresholds& thresholds = {});

// rasterFromGrid + saveRosMap (trinary, with the same thresholds written to the YAML): writes
// `<yaml stem>.pgm` beside `yaml_path` and the YAML. Returns an error message on failure, also
// for bad thresholds or a grid with nothing observed.
std::optional<std::string> saveGridAsRosMap(const OccupancyGrid& grid,
                                            const std::filesystem::path& yaml_path,
                                            const GridExportThresholds& thresholds = {});

}  // namespace irgs
