#pragma once
// The world model: everything IRGS knows about an environment, in world metres and radians.
// Maps are plain values; file formats live in map_file.hpp (JSON) and ros_map.hpp (ROS).

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/geometry/types.hpp"
#include "core/world/raster_map.hpp"

namespace irgs {

// A wall as a polyline (two points = one segment). The robot-facing side is not stored:
// thin walls reflect on both faces. `closed` joins the last point back to the first.
struct Wall {
  std::string id;
  std::vector<Vec2> points;
  bool closed = false;
  nlohmann::json extra = nlohmann::json::object();  // unknown keys, preserved on save
};

// A solid polygon obstacle (vertices in either winding; stored counter-clockwise after load).
struct Obstacle {
  std::string id;
  std::vector<Vec2> polygon;
  nlohmann::json extra = nlohmann::json::object();
};

enum class PointFeatureKind { kCorner, kEdge };  // concave corner / convex edge (000_…)

struct PointFeature {
  std::string id;
  PointFeatureKind kind = PointFeatureKind::kCorner;
  Vec2 position = Vec2::Zero();
  nlohmann::json extra = nlohmann::json::object();
};

// An sRGB colour, 8 bits a channel ("#rrggbb" in map files).
struct ColourRgb {
  int r = 0;
  int g = 0;
  int b = 0;
  friend bool operator==(const ColourRgb&, const ColourRgb&) = default;
};

// "#rrggbb" (either case) -> colour; nothing for any other text.
std::optional<ColourRgb> parseHexColour(std::string_view text);
std::string formatHexColour(const ColourRgb& colour);  // "#rrggbb", lower case

// The fluorescent red of 002_…'s markers (the camera's kMarkerRed albedo, times 255).
inline constexpr ColourRgb kDefaultMarkerColour{255, 41, 61};

// A ceiling marker (002_…: 20 cm fluorescent-red square), pose on the ceiling plane. The colour
// is what the simulated camera paints; the detector looks for the default red, so a marker of
// another colour is a painted square the robot does not recognise (a distractor).
struct CeilingMarker {
  std::string id;
  Vec2 position = Vec2::Zero();
  double heading_rad = 0.0;
  double size_m = 0.2;
  ColourRgb colour = kDefaultMarkerColour;
  nlohmann::json extra = nlohmann::json::object();
};

// A ceiling light (a fluorescent tube) from a to b on the ceiling plane.
struct CeilingLight {
  std::string id;
  Segment tube;
  double width_m = 0.1;
  nlohmann::json extra = nlohmann::json::object();
};

struct TopoNode {
  std::string id;
  Vec2 position = Vec2::Zero();
  std::string marker_id;  // ceiling marker at this node, may be empty
  nlohmann::json extra = nlohmann::json::object();
};

// An edge along a corridor (a light row). Its cost is the corridor length: `cost_m` when the
// map gives it (a corridor that bends between its nodes), otherwise the straight distance
// between the nodes (A002 "edge cost not specified").
struct TopoEdge {
  std::string from;
  std::string to;
  bool bidirectional = true;
  std::optional<double> cost_m;  // > 0 when given
  nlohmann::json extra = nlohmann::json::object();
};

struct TopoGraph {
  std::vector<TopoNode> nodes;
  std::vector<TopoEdge> edges;
  nlohmann::json extra = nlohmann::json::object();

  // The node with this id, or nullptr.
  const TopoNode* node(const std::string& id) const;
  // The edge's cost: cost_m when given, else the distance between its nodes; nothing when a
  // node is missing.
  std::optional<double> edgeCost(const TopoEdge& edge) const;
};

// An obstacle that moves on a scripted path (paper 002's dynamic obstacles: people, carts). The
// polygon is in the obstacle's own frame and is translated (not rotated) so that its origin
// follows `path` at `speed_mps`, starting at path[0] after `start_delay_s`. With `loop` the path
// closes back to its first point and repeats (two points = back and forth); without it the
// obstacle stops at the last point. Position at a time: movingObstaclePosition
// (core/world/moving_obstacle.hpp).
struct MovingObstacle {
  std::string id;
  std::vector<Vec2> polygon;  // counter-clockwise after load
  std::vector<Vec2> path;     // at least 1 point (one point: it stands still)
  double speed_mps = 0.5;
  bool loop = true;
  double start_delay_s = 0.0;
  nlohmann::json extra = nlohmann::json::object();
};

// A raster layer: a ROS map referenced by the JSON map (path relative to the map file).
struct RasterLayer {
  std::string source;  // as written in the file
  RasterMap raster;
  nlohmann::json extra = nlohmann::json::object();
  // Absolute path the raster was loaded from (not written to files). When set, saveMapFile
  // writes `source` relative to the new map file's folder so the reference keeps working.
  std::string resolved_path{};
};

// A background floor-plan image under the map (a scanned or exported drawing to trace walls on).
// Core never decodes the image: it holds the reference and the calibration; the GUI loads and
// draws it. Pixel (u, v) (u right, v down from the top-left corner) lies at
//   world = origin + R(rotation_rad) * metres_per_pixel * (u, -v).
struct FloorPlan {
  std::string source;  // as written in the file (relative to the map file's folder)
  double metres_per_pixel = 0.02;
  Vec2 origin = Vec2::Zero();  // world position of the image's top-left corner
  double rotation_rad = 0.0;
  double opacity = 0.5;  // 0..1, how strongly it shows under the map
  nlohmann::json extra = nlohmann::json::object();
  // Absolute path the image was found at (not written). When set, saveMapFile writes `source`
  // relative to the new map file's folder.
  std::string resolved_path{};

  friend bool operator==(const FloorPlan&, const FloorPlan&) = default;
};

struct WorldMap {
  static constexpr int kFormatVersion = 1;

  std::string name;
  std::vector<Wall> walls;
  std::vector<Obstacle> obstacles;
  std::vector<PointFeature> features;
  std::vector<CeilingMarker> markers;
  std::vector<CeilingLight> lights;
  TopoGraph graph;
  std::vector<MovingObstacle> moving_obstacles;  // simulated only; not in segments()
  Pose2 start;
  std::optional<RasterLayer> raster;
  std::optional<FloorPlan> floor_plan;
  double ceiling_height_m = 2.5;
  nlohmann::json extra = nlohmann::json::object();        // unknown top-level keys
  nlohmann::json start_extra = nlohmann::json::object();  // unknown keys of "start"

  // Every reflecting segment: wall pieces and obstacle edges.
  std::vector<Segment> segments() const;
  // The same segments, each with the id of the wall or obstacle it belongs to.
  struct LabelledSegment {
    Segment segment;
    std::string id;
  };
  std::vector<LabelledSegment> labelledSegments() const;
  // Bounding box of walls, obstacles, features and the raster.
  Box2 bounds() const;

  // The obstacle whose polygon contains p (boundary included), or nullptr.
  const Obstacle* obstacleAt(const Vec2& p) const;
  // Distance from p to the nearest wall piece or obstacle edge; +infinity without segments.
  double distanceToNearestSegment(const Vec2& p) const;
};

}  // namespace irgs
