#include "core/mapping/hybrid_map.hpp"

#include <cmath>
#include <stdexcept>

#include "core/world/map_file.hpp"

namespace irgs {
namespace {

// Visits the cells a segment passes through, sampled at a quarter cell (dense enough that no
// cell the segment crosses by more than a sliver is missed).
template <typename Visit>
void forSegmentCells(const OccupancyGrid& grid, const Segment& s, Visit&& visit) {
  const double step = 0.25 * grid.resolution_m();
  const double length = s.length();
  const int n = static_cast<int>(std::ceil(length / step));
  for (int k = 0; k <= n; ++k) {
    const Vec2 p = n == 0 ? s.a : Vec2(s.a + (static_cast<double>(k) / n) * (s.b - s.a));
    if (grid.isAddressable(p))
      visit(grid.cellAt(p));
  }
}

CellTag tagFromWeight(float log_odds, double occ_logit, double free_logit) {
  if (std::isnan(log_odds))
    return CellTag::kUnknown;
  if (log_odds > occ_logit)
    return CellTag::kOccupied;
  if (log_odds < free_logit)
    return CellTag::kFree;
  return CellTag::kUnknown;
}

std::pair<double, double> logits(const GridExportThresholds& t) {
  if (const auto error = gridExportThresholdsError(t))
    throw std::invalid_argument(*error);
  return {std::log(t.occupied_probability / (1.0 - t.occupied_probability)),
          std::log(t.free_probability / (1.0 - t.free_probability))};
}

}  // namespace

HybridMap HybridMap::fromGrid(OccupancyGrid grid, const FeatureExtractionParams& params) {
  HybridMap map{std::move(grid), {}};
  map.features = extractFeatures(map.grid, params);
  return map;
}

CellTag HybridMap::tagAt(const Cell& cell, const GridExportThresholds& thresholds) const {
  OccupancyGrid::CellRect rect{cell.col, cell.row, cell.col, cell.row};
  std::vector<CellTag> out;
  tags(rect, out, thresholds);
  return out.front();
}

void HybridMap::tags(const OccupancyGrid::CellRect& rect, std::vector<CellTag>& out,
                     const GridExportThresholds& thresholds) const {
  const auto [occ_logit, free_logit] = logits(thresholds);
  out.clear();
  if (rect.empty())
    return;
  std::vector<float> weights;
  grid.copyLogOdds(rect, weights);
  out.resize(weights.size());
  for (std::size_t i = 0; i < weights.size(); ++i)
    out[i] = tagFromWeight(weights[i], occ_logit, free_logit);
  const auto mark = [&](const Cell& c, CellTag tag) {
    if (c.col < rect.col0 || c.col > rect.col1 || c.row < rect.row0 || c.row > rect.row1)
      return;
    out[static_cast<std::size_t>(c.row - rect.row0) * static_cast<std::size_t>(rect.width()) +
        static_cast<std::size_t>(c.col - rect.col0)] = tag;
  };
  for (const ExtractedLine& line : features.lines)
    forSegmentCells(grid, line.segment, [&](const Cell& c) { mark(c, CellTag::kPlane); });
  for (const ExtractedPoint& p : features.points) {
    if (!grid.isAddressable(p.position, 2.0 * grid.resolution_m()))
      continue;
    const Cell centre = grid.cellAt(p.position);
    const CellTag tag = p.kind == PointFeatureKind::kCorner ? CellTag::kCorner : CellTag::kEdge;
    for (int dr = -1; dr <= 1; ++dr)
      for (int dc = -1; dc <= 1; ++dc)
        mark({centre.col + dc, centre.row + dr}, tag);
  }
}

WorldMap HybridMap::toWorldMap(const HybridMapExportOptions& options) const {
  if (const auto error = gridExportThresholdsError(options.thresholds))
    throw std::invalid_argument(*error);
  WorldMap world;
  world.name = options.name;
  world.start = options.start;
  for (std::size_t k = 0; k < features.lines.size(); ++k) {
    const ExtractedLine& line = features.lines[k];
    Wall wall;
    wall.id = "P" + std::to_string(k);
    wall.points = {line.segment.a, line.segment.b};
    world.walls.push_back(std::move(wall));
  }
  int corners = 0, edges = 0;
  for (const ExtractedPoint& p : features.points) {
    PointFeature f;
    f.kind = p.kind;
    f.id = p.kind == PointFeatureKind::kCorner ? "C" + std::to_string(corners++)
                                               : "E" + std::to_string(edges++);
    f.position = p.position;
    world.features.push_back(std::move(f));
  }
  RasterMap raster = rasterFromGrid(grid, options.thresholds);
  if (!raster.empty()) {
    RasterLayer layer;
    layer.source = options.raster_source;
    layer.raster = std::move(raster);
    world.raster = std::move(layer);
  }
  return world;
}

std::optional<std::string> saveHybridMap(const HybridMap& map,
                                         const std::filesystem::path& json_path,
                                         HybridMapExportOptions options) {
  if (const auto error = gridExportThresholdsError(options.thresholds))
    return *error;
  if (json_path.filename().empty())
    return "saveHybridMap: '" + json_path.string() + "' names no file";
  const std::string yaml_name = json_path.stem().string() + "_grid.yaml";
  if (const auto error =
          saveGridAsRosMap(map.grid, json_path.parent_path() / yaml_name, options.thresholds))
    return error;
  options.raster_source = yaml_name;
  try {
    return saveMapFile(map.toWorldMap(options), json_path);
  } catch (const std::invalid_argument& e) {  // a non-finite coordinate in the features
    return std::string(e.what());
  }
}

const char* toString(CellTag tag) {
  switch (tag) {
    case CellTag::kUnknown:
      return "unknown";
    case CellTag::kFree:
      return "free";
    case CellTag::kOccupied:
      return "occupied";
    case CellTag::kPlane:
      return "plane";
    case CellTag::kCorner:
      return "corner";
    case CellTag::kEdge:
      return "edge";
  }
  return "unknown";
}

}  // namespace irgs
