// Reading: map JSON text -> WorldMap, with a located diagnostic for every problem.
#include "core/world/map_file.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "core/world/map_file_fields.hpp"
#include "core/world/map_file_internal.hpp"
#include "core/world/ros_map.hpp"

namespace irgs {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using namespace map_file_internal;

// Deeper documents are refused before parsing: copying nested JSON recurses.
constexpr int kMaxNesting = 64;

double signedArea2(const std::vector<Vec2>& polygon) {
  double sum = 0.0;
  for (std::size_t i = 0; i < polygon.size(); ++i)
    sum += cross(polygon[i], polygon[(i + 1) % polygon.size()]);
  return sum;
}

// Reads one document into a WorldMap, collecting diagnostics.
class MapReader : private JsonFieldReader {
 public:
  MapReader(std::string_view text, std::string source, fs::path base_dir)
      : JsonFieldReader(text, std::move(source)), base_dir_(std::move(base_dir)) {}

  MapLoadResult read();

 private:
  // The map, or nothing when the document is unusable or a diagnostic is an error.
  std::optional<WorldMap> readDocument();
  bool readHeader(const json& root);
  void readStart(const json& root, WorldMap& map);
  void readRaster(const json& root, WorldMap& map);
  void readFloorPlan(const json& root, WorldMap& map);
  void readWalls(const json& root, WorldMap& map);
  void readObstacles(const json& root, WorldMap& map);
  void readFeatures(const json& root, WorldMap& map);
  void readMarkers(const json& root, WorldMap& map);
  void readLights(const json& root, WorldMap& map);
  void readGraph(const json& root, WorldMap& map);
  void readMovingObstacles(const json& root, WorldMap& map);
  void checkPlausibility(const WorldMap& map);

  fs::path base_dir_;
};

MapLoadResult MapReader::read() {
  MapLoadResult result;
  result.map = readDocument();
  result.diagnostics = takeDiagnostics();
  return result;
}

std::optional<WorldMap> MapReader::readDocument() {
  if (!checkNesting(kMaxNesting))
    return std::nullopt;
  json root;
  try {
    root = json::parse(text());
  } catch (const nlohmann::json::exception& e) {
    syntaxError(e);
    return std::nullopt;
  }
  if (!root.is_object()) {
    error("", "expected a map object {\"format\": \"irgs-map\", \"version\": 1, ...}, found " +
                  describe(root));
    return std::nullopt;
  }
  if (!readHeader(root))
    return std::nullopt;

  WorldMap map;
  if (const json* v = member(root, "", "name", false)) {
    if (auto s = string(*v, "/name"))
      map.name = *s;
  }
  if (auto h = positiveNumber(root, "", "ceiling_height_m", map.ceiling_height_m, "metres"))
    map.ceiling_height_m = *h;
  readStart(root, map);
  readRaster(root, map);
  readFloorPlan(root, map);
  readWalls(root, map);
  readObstacles(root, map);
  readFeatures(root, map);
  readMarkers(root, map);
  readLights(root, map);
  readGraph(root, map);
  readMovingObstacles(root, map);
  map.extra = extras(
      root, "",
      {"format", "version", "name", "ceiling_height_m", "start", "raster", "floor_plan", "walls",
       "obstacles", "features", "ceiling_markers", "ceiling_lights", "graph", "moving_obstacles"});
  if (hasErrors(diagnostics()))
    return std::nullopt;
  checkPlausibility(map);
  return map;
}

bool MapReader::readHeader(const json& root) {
  const json* format = member(root, "", "format", true, "\"format\": \"irgs-map\"");
  const json* version = member(root, "", "version", true, "\"version\": 1");
  if (format == nullptr || version == nullptr)
    return false;
  if (!format->is_string() || format->get<std::string>() != kMapFormatName) {
    error("/format",
          "expected \"irgs-map\", found " +
              (format->is_string() ? quote(format->get<std::string>()) : describe(*format)) +
              ": this is not an IRGS map file");
    return false;
  }
  if (!version->is_number_integer()) {
    error("/version", "expected an integer format version, found " + describe(*version));
    return false;
  }
  const auto v = version->get<std::int64_t>();
  if (v != WorldMap::kFormatVersion) {
    error("/version",
          "unsupported map format version " + std::to_string(v) + "; this IRGS reads version " +
              std::to_string(WorldMap::kFormatVersion) +
              (v > WorldMap::kFormatVersion ? " (the file is newer than this program)" : ""));
    return false;
  }
  return true;
}

void MapReader::readStart(const json& root, WorldMap& map) {
  const json* start = member(root, "", "start", false);
  if (start == nullptr) {
    warning("/start", "no start pose given; using x = 0, y = 0, theta_rad = 0");
    return;
  }
  if (!expectObject(*start, "/start", "a start pose {\"x\", \"y\", \"theta_rad\"}"))
    return;
  const json* x = member(*start, "/start", "x", true, "metres");
  const json* y = member(*start, "/start", "y", true, "metres");
  const auto xv = x ? number(*x, "/start/x") : std::nullopt;
  const auto yv = y ? number(*y, "/start/y") : std::nullopt;
  const auto theta = optionalNumber(*start, "/start", "theta_rad", 0.0);
  if (xv && yv && theta)
    map.start = {*xv, *yv, wrapAngle(*theta)};
  map.start_extra = extras(*start, "/start", {"x", "y", "theta_rad"});
}

void MapReader::readRaster(const json& root, WorldMap& map) {
  const json* raster = member(root, "", "raster", false);
  if (raster == nullptr || !expectObject(*raster, "/raster", "a raster layer {\"source\": ...}"))
    return;
  const json* source = member(*raster, "/raster", "source", true, "path of a ROS map YAML");
  json extra = extras(*raster, "/raster", {"source"});
  if (source == nullptr)
    return;
  const auto path = string(*source, "/raster/source");
  if (!path)
    return;
  if (path->empty()) {
    error("/raster/source", "must name a ROS map YAML file");
    return;
  }
  fs::path resolved = *path;
  if (resolved.is_relative())
    resolved = base_dir_ / resolved;
  RosMapLoadResult loaded = loadRosMap(resolved);
  if (!loaded.raster) {
    error("/raster/source", "cannot load the raster layer " + quote(*path) + " (" +
                                resolved.string() + "); the problems follow");
  }
  for (Diagnostic& d : loaded.diagnostics)
    add(std::move(d));
  if (!loaded.raster)
    return;
  std::error_code ec;
  const fs::path absolute = fs::absolute(resolved, ec);
  map.raster = RasterLayer{*path, std::move(*loaded.raster), std::move(extra),
                           ec ? resolved.string() : absolute.lexically_normal().string()};
}

void MapReader::readFloorPlan(const json& root, WorldMap& map) {
  const char* p = "/floor_plan";
  const json* plan = member(root, "", "floor_plan", false);
  if (plan == nullptr || !expectObject(*plan, p, "a floor plan {\"source\": \"plan.png\", ...}"))
    return;
  FloorPlan out;
  const json* source = member(*plan, p, "source", true, "path of an image file");
  const auto path = source ? string(*source, "/floor_plan/source") : std::nullopt;
  if (path && path->empty())
    error("/floor_plan/source", "must name an image file");
  const auto scale = positiveNumber(*plan, p, "metres_per_pixel", out.metres_per_pixel, "metres");
  const bool has_origin = member(*plan, p, "origin", false) != nullptr;
  const auto origin = has_origin ? pointMember(*plan, p, "origin") : std::optional<Vec2>();
  const auto rotation = optionalNumber(*plan, p, "rotation_rad", out.rotation_rad);
  const auto opacity = optionalNumber(*plan, p, "opacity", out.opacity);
  if (opacity && !(*opacity >= 0.0 && *opacity <= 1.0))
    error("/floor_plan/opacity", "expected an opacity from 0 to 1");
  out.extra = extras(*plan, p, {"source", "metres_per_pixel", "origin", "rotation_rad", "opacity"});
  if (!path || path->empty() || !scale || (has_origin && !origin) || !rotation || !opacity ||
      !(*opacity >= 0.0 && *opacity <= 1.0))
    return;
  out.source = *path;
  out.metres_per_pixel = *scale;
  if (has_origin)
    out.origin = *origin;
  out.rotation_rad = wrapAngle(*rotation);
  out.opacity = *opacity;
  fs::path resolved = *path;
  if (resolved.is_relative())
    resolved = base_dir_ / resolved;
  std::error_code ec;
  const fs::path absolute = fs::absolute(resolved, ec);
  out.resolved_path = ec ? resolved.string() : absolute.lexically_normal().string();
  if (!fs::exists(resolved, ec))
    warning("/floor_plan/source",
            "the floor-plan image " + quote(*path) + " (" + resolved.string() + ") does not exist");
  map.floor_plan = std::move(out);
}

void MapReader::readWalls(const json& root, WorldMap& map) {
  const json* walls = list(root, "walls");
  if (walls == nullptr)
    return;
  std::map<std::string, std::string> ids;
  for (std::size_t i = 0; i < walls->size(); ++i) {
    const std::string p = child("/walls", i);
    const json& w = (*walls)[i];
    if (!expectObject(w, p, "a wall {\"points\": [[x, y], ...]}"))
      continue;
    Wall wall;
    const auto wall_id = id(w, p, false, ids);
    const json* pts = member(w, p, "points", true, "[[x, y], ...] in metres, at least two");
    const auto pv = pts ? points(*pts, child(p, "points")) : std::nullopt;
    const auto closed = boolean(w, p, "closed", false);
    wall.extra = extras(w, p, {"id", "points", "closed"});
    if (!wall_id || !pv || !closed)
      continue;
    if (pv->size() < 2) {
      error(child(p, "points"),
            "a wall needs at least 2 points, found " + std::to_string(pv->size()));
      continue;
    }
    if (*closed && pv->size() < 3) {
      error(child(p, "closed"),
            "a closed wall needs at least 3 points, found " + std::to_string(pv->size()));
      continue;
    }
    for (std::size_t k = 0; k + 1 < pv->size(); ++k) {
      if ((*pv)[k] == (*pv)[k + 1])
        warning(child(child(p, "points"), k + 1),
                "repeats the previous point (a zero-length piece)");
    }
    wall.id = *wall_id;
    wall.points = *pv;
    wall.closed = *closed;
    map.walls.push_back(std::move(wall));
  }
}

void MapReader::readObstacles(const json& root, WorldMap& map) {
  const json* obstacles = list(root, "obstacles");
  if (obstacles == nullptr)
    return;
  std::map<std::string, std::string> ids;
  for (std::size_t i = 0; i < obstacles->size(); ++i) {
    const std::string p = child("/obstacles", i);
    const json& o = (*obstacles)[i];
    if (!expectObject(o, p, "an obstacle {\"polygon\": [[x, y], ...]}"))
      continue;
    Obstacle obstacle;
    const auto obstacle_id = id(o, p, false, ids);
    const json* poly = member(o, p, "polygon", true, "[[x, y], ...] in metres, at least three");
    auto pv = poly ? points(*poly, child(p, "polygon")) : std::nullopt;
    obstacle.extra = extras(o, p, {"id", "polygon"});
    if (!obstacle_id || !pv)
      continue;
    if (pv->size() >= 4 && pv->front() == pv->back()) {
      warning(child(child(p, "polygon"), pv->size() - 1),
              "the last vertex repeats the first; the polygon closes by itself, so it is dropped");
      pv->pop_back();
    }
    if (pv->size() < 3) {
      error(child(p, "polygon"),
            "a polygon needs at least 3 vertices, found " + std::to_string(pv->size()));
      continue;
    }
    const double area2 = signedArea2(*pv);
    if (!(std::abs(area2) > 1e-12)) {
      error(child(p, "polygon"), "the polygon encloses no area (its vertices are collinear)");
      continue;
    }
    if (area2 < 0.0)
      std::reverse(pv->begin(), pv->end());  // stored counter-clockwise
    obstacle.id = *obstacle_id;
    obstacle.polygon = std::move(*pv);
    map.obstacles.push_back(std::move(obstacle));
  }
}

void MapReader::readFeatures(const json& root, WorldMap& map) {
  const json* features = list(root, "features");
  if (features == nullptr)
    return;
  std::map<std::string, std::string> ids;
  for (std::size_t i = 0; i < features->size(); ++i) {
    const std::string p = child("/features", i);
    const json& f = (*features)[i];
    if (!expectObject(f, p, "a feature {\"kind\": \"corner\"|\"edge\", \"position\": [x, y]}"))
      continue;
    PointFeature feature;
    const auto feature_id = id(f, p, false, ids);
    std::optional<PointFeatureKind> kind;
    if (const json* k = member(f, p, "kind", true, "\"corner\" or \"edge\"")) {
      if (auto s = string(*k, child(p, "kind"))) {
        if (*s == "corner")
          kind = PointFeatureKind::kCorner;
        else if (*s == "edge")
          kind = PointFeatureKind::kEdge;
        else
          error(child(p, "kind"), "expected \"corner\" or \"edge\", found " + quote(*s));
      }
    }
    const auto position = pointMember(f, p, "position");
    feature.extra = extras(f, p, {"id", "kind", "position"});
    if (!feature_id || !kind || !position)
      continue;
    feature.id = *feature_id;
    feature.kind = *kind;
    feature.position = *position;
    map.features.push_back(std::move(feature));
  }
}

void MapReader::readMarkers(const json& root, WorldMap& map) {
  const json* markers = list(root, "ceiling_markers");
  if (markers == nullptr)
    return;
  std::map<std::string, std::string> ids;
  for (std::size_t i = 0; i < markers->size(); ++i) {
    const std::string p = child("/ceiling_markers", i);
    const json& m = (*markers)[i];
    if (!expectObject(m, p, "a ceiling marker {\"position\": [x, y], ...}"))
      continue;
    CeilingMarker marker;
    const auto marker_id = id(m, p, false, ids);
    const auto position = pointMember(m, p, "position");
    const auto heading = optionalNumber(m, p, "heading_rad", marker.heading_rad);
    const auto size = positiveNumber(m, p, "size_m", marker.size_m, "metres");
    std::optional<ColourRgb> colour = kDefaultMarkerColour;
    if (const json* c = member(m, p, "colour", false)) {
      const auto text = string(*c, child(p, "colour"));
      colour = text ? parseHexColour(*text) : std::nullopt;
      if (text && !colour)
        error(child(p, "colour"), "expected a colour \"#rrggbb\", found " + quote(*text));
    }
    marker.extra = extras(m, p, {"id", "position", "heading_rad", "size_m", "colour"});
    if (!marker_id || !position || !heading || !size || !colour)
      continue;
    marker.id = *marker_id;
    marker.position = *position;
    marker.heading_rad = wrapAngle(*heading);
    marker.size_m = *size;
    marker.colour = *colour;
    map.markers.push_back(std::move(marker));
  }
}

void MapReader::readLights(const json& root, WorldMap& map) {
  const json* lights = list(root, "ceiling_lights");
  if (lights == nullptr)
    return;
  std::map<std::string, std::string> ids;
  for (std::size_t i = 0; i < lights->size(); ++i) {
    const std::string p = child("/ceiling_lights", i);
    const json& l = (*lights)[i];
    if (!expectObject(l, p, "a ceiling light {\"a\": [x, y], \"b\": [x, y]}"))
      continue;
    CeilingLight light;
    const auto light_id = id(l, p, false, ids);
    const auto a = pointMember(l, p, "a");
    const auto b = pointMember(l, p, "b");
    const auto width = positiveNumber(l, p, "width_m", light.width_m, "metres");
    light.extra = extras(l, p, {"id", "a", "b", "width_m"});
    if (!light_id || !a || !b || !width)
      continue;
    if (*a == *b) {
      error(child(p, "b"), "a light tube needs two different end points");
      continue;
    }
    light.id = *light_id;
    light.tube = {*a, *b};
    light.width_m = *width;
    map.lights.push_back(std::move(light));
  }
}

void MapReader::readGraph(const json& root, WorldMap& map) {
  const json* graph = member(root, "", "graph", false);
  if (graph == nullptr ||
      !expectObject(*graph, "/graph", "a topological graph {\"nodes\": [...], \"edges\": [...]}"))
    return;
  map.graph.extra = extras(*graph, "/graph", {"nodes", "edges"});
  std::set<std::string> marker_ids;
  for (const CeilingMarker& m : map.markers)
    marker_ids.insert(m.id);

  std::map<std::string, std::string> node_ids;
  if (const json* nodes = member(*graph, "/graph", "nodes", false)) {
    if (!nodes->is_array()) {
      error("/graph/nodes", "expected an array of nodes, found " + describe(*nodes));
    } else {
      for (std::size_t i = 0; i < nodes->size(); ++i) {
        const std::string p = child("/graph/nodes", i);
        const json& n = (*nodes)[i];
        if (!expectObject(n, p, "a node {\"id\": ..., \"position\": [x, y]}"))
          continue;
        TopoNode node;
        const auto node_id = id(n, p, true, node_ids);
        const auto position = pointMember(n, p, "position");
        std::optional<std::string> marker = std::string();
        if (const json* m = member(n, p, "marker", false)) {
          marker = string(*m, child(p, "marker"));
          if (marker && !marker->empty() && marker_ids.count(*marker) == 0) {
            error(child(p, "marker"), "names the unknown ceiling marker " + quote(*marker));
            marker.reset();
          }
        }
        node.extra = extras(n, p, {"id", "position", "marker"});
        if (!node_id || !position || !marker)
          continue;
        node.id = *node_id;
        node.position = *position;
        node.marker_id = *marker;
        map.graph.nodes.push_back(std::move(node));
      }
    }
  }

  if (const json* edges = member(*graph, "/graph", "edges", false)) {
    if (!edges->is_array()) {
      error("/graph/edges", "expected an array of edges, found " + describe(*edges));
      return;
    }
    std::set<std::pair<std::string, std::string>> seen;
    for (std::size_t i = 0; i < edges->size(); ++i) {
      const std::string p = child("/graph/edges", i);
      const json& e = (*edges)[i];
      if (!expectObject(e, p, "an edge {\"from\": id, \"to\": id}"))
        continue;
      TopoEdge edge;
      std::optional<std::string> ends[2];
      const char* keys[2] = {"from", "to"};
      for (int k = 0; k < 2; ++k) {
        const json* v = member(e, p, keys[k], true, "a node id");
        if (v == nullptr)
          continue;
        ends[k] = string(*v, child(p, keys[k]));
        if (ends[k] && node_ids.count(*ends[k]) == 0) {
          error(child(p, keys[k]), "names the unknown node " + quote(*ends[k]));
          ends[k].reset();
        }
      }
      const auto bidirectional = boolean(e, p, "bidirectional", true);
      std::optional<double> cost;
      bool cost_ok = true;
      if (member(e, p, "cost_m", false) != nullptr) {
        cost = positiveNumber(e, p, "cost_m", 1.0, "metres");
        cost_ok = cost.has_value();
      }
      edge.extra = extras(e, p, {"from", "to", "bidirectional", "cost_m"});
      if (!ends[0] || !ends[1] || !bidirectional || !cost_ok)
        continue;
      edge.cost_m = cost;
      if (*ends[0] == *ends[1]) {
        error(child(p, "to"),
              "an edge must join two different nodes (both are " + quote(*ends[0]) + ")");
        continue;
      }
      if (!seen.emplace(*ends[0], *ends[1]).second)
        warning(p, "repeats an earlier edge from " + quote(*ends[0]) + " to " + quote(*ends[1]));
      edge.from = *ends[0];
      edge.to = *ends[1];
      edge.bidirectional = *bidirectional;
      map.graph.edges.push_back(std::move(edge));
    }
  }
}

void MapReader::readMovingObstacles(const json& root, WorldMap& map) {
  const json* movers = list(root, "moving_obstacles");
  if (movers == nullptr)
    return;
  std::map<std::string, std::string> ids;
  for (std::size_t i = 0; i < movers->size(); ++i) {
    const std::string p = child("/moving_obstacles", i);
    const json& o = (*movers)[i];
    if (!expectObject(o, p,
                      "a moving obstacle {\"polygon\": [[x, y], ...], \"path\": [[x, y], ...]}"))
      continue;
    MovingObstacle mover;
    const auto mover_id = id(o, p, false, ids);
    const json* poly =
        member(o, p, "polygon", true, "[[x, y], ...] in metres around the obstacle's origin");
    auto pv = poly ? points(*poly, child(p, "polygon")) : std::nullopt;
    const json* path = member(o, p, "path", true, "[[x, y], ...] waypoints in metres");
    auto wp = path ? points(*path, child(p, "path")) : std::nullopt;
    const auto speed = positiveNumber(o, p, "speed_mps", mover.speed_mps, "metres per second");
    const auto loop = boolean(o, p, "loop", mover.loop);
    const auto delay_read = optionalNumber(o, p, "start_delay_s", mover.start_delay_s);
    const double delay = delay_read.value_or(-1.0);
    if (delay_read && delay < 0.0)
      error(child(p, "start_delay_s"), "expected a delay >= 0 seconds, found a negative number");
    mover.extra = extras(o, p, {"id", "polygon", "path", "speed_mps", "loop", "start_delay_s"});
    if (pv && pv->size() < 3) {
      error(child(p, "polygon"),
            "a polygon needs at least 3 vertices, found " + std::to_string(pv->size()));
      pv.reset();
    } else if (pv && !(std::abs(signedArea2(*pv)) > 1e-12)) {
      error(child(p, "polygon"), "the polygon encloses no area (its vertices are collinear)");
      pv.reset();
    }
    if (wp && wp->empty()) {
      error(child(p, "path"), "a path needs at least 1 waypoint, found none");
      wp.reset();
    }
    if (!mover_id || !pv || !wp || !speed || !loop || delay < 0.0)
      continue;
    if (signedArea2(*pv) < 0.0)
      std::reverse(pv->begin(), pv->end());  // stored counter-clockwise
    mover.id = *mover_id;
    mover.polygon = std::move(*pv);
    mover.path = std::move(*wp);
    mover.speed_mps = *speed;
    mover.loop = *loop;
    mover.start_delay_s = delay;
    map.moving_obstacles.push_back(std::move(mover));
  }
}

void MapReader::checkPlausibility(const WorldMap& map) {
  if (map.walls.empty() && map.obstacles.empty() && !map.raster)
    warning("", "the map has no walls, obstacles or raster layer");
  if (const Obstacle* o = map.obstacleAt(map.start.position()))
    warning("/start", "the start pose lies inside obstacle " +
                          (o->id.empty() ? std::string("(unnamed)") : quote(o->id)));
}

}  // namespace

MapLoadResult parseMapJson(std::string_view text, const std::string& source_name,
                           const fs::path& base_dir) {
  MapReader reader(text, source_name, base_dir);
  try {
    return reader.read();
  } catch (const std::exception& e) {
    // Not expected: every access above is type-checked. Kept so a bug can never crash a caller.
    MapLoadResult result;
    result.diagnostics.push_back(
        {Severity::kError, source_name, 0, 0, {}, std::string("internal error: ") + e.what()});
    return result;
  }
}

}  // namespace irgs
