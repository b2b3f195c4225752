#pragma once
// The feature map the stereo-sonar EKF of paper 000 matches against (digest 1.3, 1.6): wall faces
// as lines in robot-facing normal form (A000-9), and corner/edge points.

#include <string>
#include <vector>

#include "core/geometry/types.hpp"
#include "core/world/wall_model.hpp"
#include "core/world/world_map.hpp"

namespace irgs {

struct MapWallFace {
  std::string id;     // the wall's (or obstacle's) id
  WallLine line;      // (P_R, phi, P_V) as in Table 1
  FacingLine facing;  // robot-facing form used by (16), (17), (42), (46)
  Segment segment;    // the piece of wall the face belongs to (for display and diagnostics)
};

struct MapPoint {
  std::string id;
  PointFeatureKind kind = PointFeatureKind::kCorner;
  Vec2 position = Vec2::Zero();
};

struct LocalizationMap {
  std::vector<MapWallFace> walls;
  std::vector<MapPoint> points;
};

// Both faces of every wall piece and obstacle edge (thin walls reflect on both sides; the
// matching angle test (42) separates the faces, which differ by pi), and every point feature.
// Zero-length pieces are skipped.
LocalizationMap buildLocalizationMap(const WorldMap& map);

}  // namespace irgs
