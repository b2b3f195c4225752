#include "core/mapping/grid_export.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "core/world/ros_map.hpp"

namespace irgs {

std::optional<std::string> gridExportThresholdsError(const GridExportThresholds& thresholds) {
  const double occ = thresholds.occupied_probability, fr = thresholds.free_probability;
  if (!std::isfinite(occ) || !std::isfinite(fr))
    return "grid export thresholds must be finite";
  if (!(0.0 < fr && fr < occ && occ < 1.0))
    return "grid export thresholds must satisfy 0 < free_probability (" + std::to_string(fr) +
           ") < occupied_probability (" + std::to_string(occ) + ") < 1";
  if (thresholds.padding_cells < 0)
    return "grid export padding_cells must be >= 0, got " +
           std::to_string(thresholds.padding_cells);
  // Keeps width * height well inside int and std::size_t (a 1 cm grid 100 m wide is 10^4).
  if (thresholds.padding_cells > (1 << 16))
    return "grid export padding_cells must be <= 65536, got " +
           std::to_string(thresholds.padding_cells);
  return std::nullopt;
}

RasterMap rasterFromGrid(const OccupancyGrid& grid, const GridExportThresholds& thresholds) {
  if (const auto error = gridExportThresholdsError(thresholds))
    throw std::invalid_argument(*error);
  RasterMap map;
  map.resolution_m = grid.resolution_m();
  const OccupancyGrid::CellRect observed = grid.observedCellRect();
  if (observed.empty())
    return map;

  // Compare log-odds against the thresholds' logits instead of converting every cell to a
  // probability: logit is monotonic, so p > t <=> l > log(t / (1 - t)).
  const double occ_logit =
      std::log(thresholds.occupied_probability / (1.0 - thresholds.occupied_probability));
  const double free_logit =
      std::log(thresholds.free_probability / (1.0 - thresholds.free_probability));

  const int pad = thresholds.padding_cells;
  const long long width = static_cast<long long>(observed.width()) + 2LL * pad;
  const long long height = static_cast<long long>(observed.height()) + 2LL * pad;
  if (width * height > kMaxRasterCells)
    throw std::invalid_argument("rasterFromGrid: the observed area (" + std::to_string(width) +
                                " x " + std::to_string(height) +
                                " cells) is too large for a raster");
  map.width = static_cast<int>(width);
  map.height = static_cast<int>(height);
  const double res = grid.resolution_m();
  map.origin = Pose2{(observed.col0 - pad) * res, (observed.row0 - pad) * res, 0.0};
  map.cells.assign(static_cast<std::size_t>(width) * static_cast<std::size_t>(height),
                   RasterMap::kUnknown);

  std::vector<float> log_odds;
  grid.copyLogOdds(observed, log_odds);
  const std::size_t src_width = static_cast<std::size_t>(observed.width());
  for (int r = 0; r < observed.height(); ++r) {
    const float* src = log_odds.data() + static_cast<std::size_t>(r) * src_width;
    std::int8_t* dst = &map.at(pad, r + pad);
    for (std::size_t c = 0; c < src_width; ++c) {
      const float l = src[c];
      if (std::isnan(l))
        continue;  // unknown already
      if (l > occ_logit)
        dst[c] = RasterMap::kOccupied;
      else if (l < free_logit)
        dst[c] = RasterMap::kFree;
    }
  }
  return map;
}

std::optional<std::string> saveGridAsRosMap(const OccupancyGrid& grid,
                                            const std::filesystem::path& yaml_path,
                                            const GridExportThresholds& thresholds) {
  if (const auto error = gridExportThresholdsError(thresholds))
    return *error;
  RasterMap raster;
  try {
    raster = rasterFromGrid(grid, thresholds);
  } catch (const std::invalid_argument& e) {
    return std::string(e.what());
  }
  if (raster.empty())
    return std::string("the grid has no observed cells to export");
  RosMapSaveOptions options;
  options.mode = RosMapMode::kTrinary;
  options.occupied_thresh = thresholds.occupied_probability;
  options.free_thresh = thresholds.free_probability;
  return saveRosMap(raster, yaml_path, options);
}

}  // namespace irgs
