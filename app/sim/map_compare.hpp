#pragma once
// Scores a built map against another built map instead of the true map: the reference is a map
// an earlier run saved (grid.yaml + grid.pgm, e.g. the in-process run of the same scenario), and
// its occupied cells play the part of the true surfaces in scoreMap (core/mapping/map_score.hpp):
// each side's occupied cells matched within the tolerance, as precision, recall and F1. F1 is
// symmetric in the two maps (precision and recall swap), so it measures how far two runs agree.

#include <filesystem>
#include <optional>
#include <string>

#include "core/mapping/map_score.hpp"
#include "core/mapping/occupancy_grid.hpp"
#include "core/planning/planning_grid.hpp"
#include "core/world/raster_map.hpp"

namespace irgs::app {

// The scoring cells (resolution_m, aligned to the world origin as the built grid's cells are)
// that hold at least one occupied raster cell (value >= occupied_value), over the raster's
// extent grown by margin_m on every side so that a built map reaching a little further still
// lands inside. Throws std::invalid_argument for a non-positive resolution, a negative margin,
// an empty raster or one whose cells do not match its size.
PlanningGrid occupiedScoringGrid(const RasterMap& reference, double resolution_m,
                                 int occupied_value = 65, double margin_m = 1.0);

struct MapAgreement {
  std::optional<MapScore> score;  // empty when error is set
  std::string error;              // the reference could not be read (file, line, why)
};

// Loads the reference map (ROS map_server YAML) and scores `built` against its occupied cells.
// Never throws for a bad file: the reason is in error.
MapAgreement compareWithSavedMap(const OccupancyGrid& built, const std::filesystem::path& yaml,
                                 const MapScoreOptions& options = {});

}  // namespace irgs::app
