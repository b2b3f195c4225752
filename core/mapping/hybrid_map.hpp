#pragma once
// The hybrid map of 003_… (section 3.2, digest 4.4): the weighted 1 cm occupancy grid together
// with the plane, corner and edge features extracted from it. The grid serves avoidance and
// planning, the features serve localisation (the paper-000 EKF matches walls, corners and edges)
// and a compact, editable map file.
//
// Per-cell encoding (digest 4.4 [A]): each cell has a weight (the grid's log-odds) and a tag,
// unknown / free / occupied from the weight, overridden by plane / corner / edge where an
// extracted feature passes through the cell.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/mapping/feature_extraction.hpp"
#include "core/mapping/grid_export.hpp"
#include "core/mapping/occupancy_grid.hpp"
#include "core/world/world_map.hpp"

namespace irgs {

enum class CellTag : std::uint8_t { kUnknown, kFree, kOccupied, kPlane, kCorner, kEdge };

struct HybridMapExportOptions {
  std::string name = "built map";
  Pose2 start;  // written as the map's start pose
  // How the grid becomes the raster layer (and the ROS map saveHybridMap writes).
  GridExportThresholds thresholds;
  // The raster layer's `source` (path of the ROS map YAML relative to the map file); empty
  // keeps the raster in memory only. saveHybridMap fills it.
  std::string raster_source;
};

struct HybridMap {
  OccupancyGrid grid;
  FeatureExtractionResult features;

  // Extracts the features of `grid` (extractFeatures; throws std::invalid_argument for bad
  // parameters).
  static HybridMap fromGrid(OccupancyGrid grid, const FeatureExtractionParams& params = {});

  // The tag of one cell: corner/edge within one cell of a point feature, plane on a line's
  // cells, otherwise from the weight with `thresholds` (never-observed cells are unknown).
  CellTag tagAt(const Cell& cell, const GridExportThresholds& thresholds = {}) const;
  // Tags of rect's cells, row-major from (col0, row0) (row0 = smallest y), for drawing.
  void tags(const OccupancyGrid::CellRect& rect, std::vector<CellTag>& out,
            const GridExportThresholds& thresholds = {}) const;

  // The features as a WorldMap: each line a two-point wall "P<k>", corners "C<k>" and edges
  // "E<k>" in the feature layer, the grid as the raster layer (trinary, rasterFromGrid) when
  // anything is observed. buildLocalizationMap accepts the result. Throws
  // std::invalid_argument for thresholds that gridExportThresholdsError rejects or a grid too
  // large for a raster (rasterFromGrid).
  WorldMap toWorldMap(const HybridMapExportOptions& options = {}) const;
};

// Writes the hybrid map as an IRGS map file at `json_path` with its grid as a ROS map beside it
// (`<stem>_grid.yaml` + `<stem>_grid.pgm`, referenced by the map's raster layer), so loadMapFile
// reads walls, features and raster back. Returns an error message on failure (bad thresholds,
// nothing observed, a grid too large for a raster, I/O).
std::optional<std::string> saveHybridMap(const HybridMap& map,
                                         const std::filesystem::path& json_path,
                                         HybridMapExportOptions options = {});

const char* toString(CellTag tag);

}  // namespace irgs
