#include "core/estimation/localization_map.hpp"

namespace irgs {

LocalizationMap buildLocalizationMap(const WorldMap& map) {
  LocalizationMap out;
  auto add = [&out](const Vec2& a, const Vec2& b, const std::string& id) {
    const Segment seg{a, b};
    if (!(seg.length() > 0.0))
      return;
    for (const WallLine& line : wallLineFaces(seg))
      out.walls.push_back({id, line, robotFacing(line), seg});
  };
  for (const WorldMap::LabelledSegment& piece : map.labelledSegments())
    add(piece.segment.a, piece.segment.b, piece.id);
  for (const PointFeature& f : map.features)
    out.points.push_back({f.id, f.kind, f.position});
  return out;
}

}  // namespace irgs
