#include "app/sim/map_compare.hpp"

#include <cmath>
#include <stdexcept>

#include "core/world/ros_map.hpp"

namespace irgs::app {

PlanningGrid occupiedScoringGrid(const RasterMap& reference, double resolution_m,
                                 int occupied_value, double margin_m) {
  if (!std::isfinite(resolution_m) || resolution_m <= 0.0)
    throw std::invalid_argument("occupiedScoringGrid: resolution must be finite and > 0");
  if (!std::isfinite(margin_m) || margin_m < 0.0)
    throw std::invalid_argument("occupiedScoringGrid: margin must be finite and >= 0");
  if (reference.empty() ||
      reference.cells.size() !=
          static_cast<std::size_t>(reference.width) * static_cast<std::size_t>(reference.height) ||
      !std::isfinite(reference.resolution_m) || reference.resolution_m <= 0.0)
    throw std::invalid_argument("occupiedScoringGrid: empty or inconsistent reference raster");
  // Scoring cells on the lattice k * resolution_m, like the truth grid of scoreMap's callers,
  // so the cell a built 1 cm cell falls into does not depend on the reference's origin.
  const Box2 b = reference.bounds();
  const double x0 = std::floor((b.min.x() - margin_m) / resolution_m) * resolution_m;
  const double y0 = std::floor((b.min.y() - margin_m) / resolution_m) * resolution_m;
  const double w = std::ceil((b.max.x() + margin_m - x0) / resolution_m);
  const double h = std::ceil((b.max.y() + margin_m - y0) / resolution_m);
  if (w * h > static_cast<double>(PlanningGrid::kMaxCells))
    throw std::invalid_argument("occupiedScoringGrid: the reference is too large to score");
  PlanningGrid grid =
      PlanningGrid::freeGrid(static_cast<int>(w), static_cast<int>(h), resolution_m, Vec2(x0, y0));
  for (int row = 0; row < reference.height; ++row)
    for (int col = 0; col < reference.width; ++col)
      if (reference.at(col, row) >= occupied_value)
        if (const auto c = grid.worldToCell(reference.cellCentre(col, row)))
          grid.setBlocked(*c, true);
  return grid;
}

MapAgreement compareWithSavedMap(const OccupancyGrid& built, const std::filesystem::path& yaml,
                                 const MapScoreOptions& options) {
  MapAgreement out;
  const RosMapLoadResult loaded = loadRosMap(yaml);
  if (!loaded.raster) {
    out.error = "cannot read the reference map " + yaml.string();
    for (const Diagnostic& d : loaded.diagnostics)
      out.error += "\n  " + d.toString();
    return out;
  }
  // The saved map is trinary: occupied cells read back as 100, free as 0, unknown as -1.
  try {
    out.score = scoreMap(built, occupiedScoringGrid(*loaded.raster, options.resolution_m), options);
  } catch (const std::invalid_argument& e) {
    out.error = "cannot score against " + yaml.string() + ": " + e.what();
  }
  return out;
}

}  // namespace irgs::app
