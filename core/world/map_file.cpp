#include "core/world/map_file.hpp"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <map>
#include <memory>
#include <set>
#include <stdexcept>

#include "core/io/atomic_file.hpp"
#include "core/io/json_locator.hpp"
#include "core/world/raster_world.hpp"
#include "core/world/ros_map.hpp"

namespace irgs {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using OrderedJson = nlohmann::ordered_json;

// Deeper documents are refused before parsing: copying nested JSON recurses.
constexpr int kMaxNesting = 64;
constexpr double kStartClearance_m = 0.25;

std::string describe(const json& v) {
  switch (v.type()) {
    case json::value_t::null:
      return "null";
    case json::value_t::boolean:
      return v.get<bool>() ? "true" : "false";
    case json::value_t::string:
      return "a string";
    case json::value_t::array:
      return "an array";
    case json::value_t::object:
      return "an object";
    case json::value_t::number_integer:
    case json::value_t::number_unsigned:
    case json::value_t::number_float:
      return "a number";
    default:
      return "an unsupported value";
  }
}

std::string child(const std::string& pointer, std::string_view key) {
  return pointer + "/" + JsonLocator::escapeToken(key);
}
std::string child(const std::string& pointer, std::size_t index) {
  return pointer + "/" + std::to_string(index);
}

std::string quote(std::string_view s) {
  return "'" + std::string(s) + "'";
}

double signedArea2(const std::vector<Vec2>& polygon) {
  double sum = 0.0;
  for (std::size_t i = 0; i < polygon.size(); ++i)
    sum += cross(polygon[i], polygon[(i + 1) % polygon.size()]);
  return sum;
}

// Reads one document into a WorldMap, collecting diagnostics.
class MapReader {
 public:
  MapReader(std::string_view text, std::string source, fs::path base_dir)
      : text_(text), source_(std::move(source)), base_dir_(std::move(base_dir)) {}

  MapLoadResult read();

 private:
  // --- diagnostics -------------------------------------------------------------------------
  void report(Severity severity, const std::string& pointer, std::string message) {
    if (!locator_)
      locator_ = std::make_unique<JsonLocator>(text_);
    const TextPosition at = locator_->locate(pointer);
    result_.diagnostics.push_back(
        {severity, source_, at.line, at.column, pointer, std::move(message)});
  }
  void error(const std::string& pointer, std::string message) {
    report(Severity::kError, pointer, std::move(message));
  }
  void warning(const std::string& pointer, std::string message) {
    report(Severity::kWarning, pointer, std::move(message));
  }

  // --- typed access; each reports its own problem and returns nothing ----------------------
  bool expectObject(const json& v, const std::string& pointer, std::string_view what) {
    if (v.is_object())
      return true;
    error(pointer, "expected " + std::string(what) + " (an object), found " + describe(v));
    return false;
  }
  // Member `key` of `obj`, or nullptr (reported when required).
  const json* member(const json& obj, const std::string& pointer, const char* key, bool required,
                     std::string_view hint = {}) {
    const auto it = obj.find(key);
    if (it != obj.end())
      return &*it;
    if (required) {
      std::string message = std::string("missing required key '") + key + "'";
      if (!hint.empty())
        message += " (" + std::string(hint) + ")";
      error(child(pointer, key), std::move(message));
    }
    return nullptr;
  }
  std::optional<double> number(const json& v, const std::string& pointer) {
    if (!v.is_number()) {
      error(pointer, "expected a number, found " + describe(v));
      return std::nullopt;
    }
    const double d = v.get<double>();
    if (!std::isfinite(d)) {
      error(pointer, "the number is not finite");
      return std::nullopt;
    }
    return d;
  }
  // Optional number member with a default; nothing when present but invalid.
  std::optional<double> optionalNumber(const json& obj, const std::string& pointer, const char* key,
                                       double fallback) {
    const json* v = member(obj, pointer, key, false);
    return v == nullptr ? std::optional<double>(fallback) : number(*v, child(pointer, key));
  }
  std::optional<double> positiveNumber(const json& obj, const std::string& pointer, const char* key,
                                       double fallback, const char* unit) {
    auto v = optionalNumber(obj, pointer, key, fallback);
    if (v && !(*v > 0.0)) {
      error(child(pointer, key), std::string("must be a positive number of ") + unit);
      return std::nullopt;
    }
    return v;
  }
  std::optional<std::string> string(const json& v, const std::string& pointer) {
    if (!v.is_string()) {
      error(pointer, "expected a string, found " + describe(v));
      return std::nullopt;
    }
    return v.get<std::string>();
  }
  std::optional<bool> boolean(const json& obj, const std::string& pointer, const char* key,
                              bool fallback) {
    const json* v = member(obj, pointer, key, false);
    if (v == nullptr)
      return fallback;
    if (!v->is_boolean()) {
      error(child(pointer, key), "expected true or false, found " + describe(*v));
      return std::nullopt;
    }
    return v->get<bool>();
  }
  std::optional<Vec2> point(const json& v, const std::string& pointer) {
    if (!v.is_array() || v.size() != 2) {
      error(pointer, "expected a point [x, y] in metres, found " +
                         (v.is_array() ? "an array of " + std::to_string(v.size()) + " values"
                                       : describe(v)));
      return std::nullopt;
    }
    const auto x = number(v[0], child(pointer, std::size_t{0}));
    const auto y = number(v[1], child(pointer, std::size_t{1}));
    if (!x || !y)
      return std::nullopt;
    return Vec2(*x, *y);
  }
  std::optional<Vec2> pointMember(const json& obj, const std::string& pointer, const char* key) {
    const json* v = member(obj, pointer, key, true, "[x, y] in metres");
    return v == nullptr ? std::nullopt : point(*v, child(pointer, key));
  }
  std::optional<std::vector<Vec2>> points(const json& v, const std::string& pointer) {
    if (!v.is_array()) {
      error(pointer, "expected an array of points [[x, y], ...], found " + describe(v));
      return std::nullopt;
    }
    std::vector<Vec2> out;
    bool ok = true;
    for (std::size_t i = 0; i < v.size(); ++i) {
      if (auto p = point(v[i], child(pointer, i)))
        out.push_back(*p);
      else
        ok = false;
    }
    return ok ? std::optional(std::move(out)) : std::nullopt;
  }
  // The array member `key` of the root (absent = empty).
  const json* list(const json& root, const char* key) {
    const json* v = member(root, "", key, false);
    if (v != nullptr && !v->is_array()) {
      error(child("", key), "expected an array, found " + describe(*v));
      return nullptr;
    }
    return v;
  }
  // Unknown members of obj (to keep); warns about those not marked as extensions with "x-".
  json extras(const json& obj, const std::string& pointer,
              std::initializer_list<std::string_view> known) {
    json out = json::object();
    for (auto it = obj.begin(); it != obj.end(); ++it) {
      if (std::find(known.begin(), known.end(), it.key()) != known.end())
        continue;
      if (it.key().rfind("x-", 0) != 0)
        warning(child(pointer, it.key()), "unknown key " + quote(it.key()) + " is kept as it is");
      out[it.key()] = it.value();
    }
    return out;
  }
  // Optional "id": a string, unique within its list (`seen` maps id -> pointer of first use).
  std::optional<std::string> id(const json& obj, const std::string& pointer, bool required,
                                std::map<std::string, std::string>& seen) {
    const json* v = member(obj, pointer, "id", required);
    if (v == nullptr)
      return required ? std::nullopt : std::optional<std::string>(std::string());
    auto s = string(*v, child(pointer, "id"));
    if (!s)
      return std::nullopt;
    if (s->empty()) {
      if (required)
        error(child(pointer, "id"), "must not be empty");
      return required ? std::nullopt : s;
    }
    const auto [it, inserted] = seen.emplace(*s, pointer);
    if (!inserted) {
      error(child(pointer, "id"),
            "duplicate id " + quote(*s) + " (first used by " + it->second + ")");
      return std::nullopt;
    }
    return s;
  }

  // --- sections ----------------------------------------------------------------------------
  bool readHeader(const json& root);
  void readStart(const json& root, WorldMap& map);
  void readRaster(const json& root, WorldMap& map);
  void readWalls(const json& root, WorldMap& map);
  void readObstacles(const json& root, WorldMap& map);
  void readFeatures(const json& root, WorldMap& map);
  void readMarkers(const json& root, WorldMap& map);
  void readLights(const json& root, WorldMap& map);
  void readGraph(const json& root, WorldMap& map);
  void checkPlausibility(const WorldMap& map);
  void syntaxError(const nlohmann::json::exception& e);

  std::string_view text_;
  std::string source_;
  fs::path base_dir_;
  std::unique_ptr<JsonLocator> locator_;
  MapLoadResult result_;
};

MapLoadResult MapReader::read() {
  if (const NestingDepth depth = maxNestingDepth(text_); depth.depth > kMaxNesting) {
    // No full locator here: its table of pointers would grow with the square of the depth.
    const TextPosition at = JsonLocator::positionIn(text_, depth.offset);
    result_.diagnostics.push_back(
        {Severity::kError, source_, at.line, at.column, JsonLocator::pointerIn(text_, depth.offset),
         "values are nested deeper than " + std::to_string(kMaxNesting) + " levels"});
    return std::move(result_);
  }
  json root;
  try {
    root = json::parse(text_);
  } catch (const nlohmann::json::exception& e) {
    syntaxError(e);
    return std::move(result_);
  }
  if (!root.is_object()) {
    error("", "expected a map object {\"format\": \"irgs-map\", \"version\": 1, ...}, found " +
                  describe(root));
    return std::move(result_);
  }
  if (!readHeader(root))
    return std::move(result_);

  WorldMap map;
  if (const json* v = member(root, "", "name", false)) {
    if (auto s = string(*v, "/name"))
      map.name = *s;
  }
  if (auto h = positiveNumber(root, "", "ceiling_height_m", map.ceiling_height_m, "metres"))
    map.ceiling_height_m = *h;
  readStart(root, map);
  readRaster(root, map);
  readWalls(root, map);
  readObstacles(root, map);
  readFeatures(root, map);
  readMarkers(root, map);
  readLights(root, map);
  readGraph(root, map);
  map.extra = extras(root, "",
                     {"format", "version", "name", "ceiling_height_m", "start", "raster", "walls",
                      "obstacles", "features", "ceiling_markers", "ceiling_lights", "graph"});
  if (!hasErrors(result_.diagnostics)) {
    checkPlausibility(map);
    result_.map = std::move(map);
  }
  return std::move(result_);
}

void MapReader::syntaxError(const nlohmann::json::exception& e) {
  locator_ = std::make_unique<JsonLocator>(text_);
  std::size_t offset = text_.size();
  std::string what = e.what();
  std::string reason = what;
  if (const auto* pe = dynamic_cast<const nlohmann::json::parse_error*>(&e)) {
    offset = pe->byte > 0 ? pe->byte - 1 : 0;
    // "[json.exception.parse_error.101] parse error at line 3, column 7: <reason>"
    if (const auto colon = what.find(": "); colon != std::string::npos)
      reason = what.substr(colon + 2);
  } else {
    // e.g. "[json.exception.out_of_range.406] number overflow parsing '1e400'"
    if (const auto bracket = what.find("] "); bracket != std::string::npos)
      reason = what.substr(bracket + 2);
    const auto open = what.find('\'');
    const auto close = what.rfind('\'');
    if (open != std::string::npos && close > open) {
      const auto at = text_.find(what.substr(open + 1, close - open - 1));
      if (at != std::string_view::npos)
        offset = at;
    }
    if (reason.find("number overflow") != std::string::npos)
      reason += " (numbers must be finite)";
  }
  const TextPosition at = locator_->positionOf(offset);
  result_.diagnostics.push_back({Severity::kError, source_, at.line, at.column,
                                 locator_->pointerAt(offset), "invalid JSON: " + reason});
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
    result_.diagnostics.push_back(std::move(d));
  if (!loaded.raster)
    return;
  std::error_code ec;
  const fs::path absolute = fs::absolute(resolved, ec);
  map.raster = RasterLayer{*path, std::move(*loaded.raster), std::move(extra),
                           ec ? resolved.string() : absolute.lexically_normal().string()};
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
    marker.extra = extras(m, p, {"id", "position", "heading_rad", "size_m"});
    if (!marker_id || !position || !heading || !size)
      continue;
    marker.id = *marker_id;
    marker.position = *position;
    marker.heading_rad = wrapAngle(*heading);
    marker.size_m = *size;
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
      edge.extra = extras(e, p, {"from", "to", "bidirectional"});
      if (!ends[0] || !ends[1] || !bidirectional)
        continue;
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

void MapReader::checkPlausibility(const WorldMap& map) {
  if (map.walls.empty() && map.obstacles.empty() && !map.raster)
    warning("", "the map has no walls, obstacles or raster layer");
  if (const Obstacle* o = map.obstacleAt(map.start.position()))
    warning("/start", "the start pose lies inside obstacle " +
                          (o->id.empty() ? std::string("(unnamed)") : quote(o->id)));
}

// --- writing -------------------------------------------------------------------------------

double finite(double v, const std::string& pointer) {
  if (!std::isfinite(v))
    throw std::invalid_argument("serializeMap: the value at " + pointer + " is not finite");
  return v;
}

OrderedJson pointJson(const Vec2& p, const std::string& pointer) {
  return OrderedJson::array({finite(p.x(), pointer + "/0"), finite(p.y(), pointer + "/1")});
}

OrderedJson pointsJson(const std::vector<Vec2>& points, const std::string& pointer) {
  OrderedJson out = OrderedJson::array();
  for (std::size_t i = 0; i < points.size(); ++i)
    out.push_back(pointJson(points[i], child(pointer, i)));
  return out;
}

// Appends unknown keys that do not collide with the ones already written.
void appendExtra(OrderedJson& out, const json& extra) {
  if (!extra.is_object())
    return;
  for (auto it = extra.begin(); it != extra.end(); ++it) {
    if (!out.contains(it.key()))
      out[it.key()] = OrderedJson(it.value());
  }
}

OrderedJson toJson(const WorldMap& map, const std::string& raster_source) {
  OrderedJson root = OrderedJson::object();
  root["format"] = kMapFormatName;
  root["version"] = WorldMap::kFormatVersion;
  root["name"] = map.name;
  root["ceiling_height_m"] = finite(map.ceiling_height_m, "/ceiling_height_m");

  OrderedJson start = OrderedJson::object();
  start["x"] = finite(map.start.x, "/start/x");
  start["y"] = finite(map.start.y, "/start/y");
  start["theta_rad"] = finite(map.start.theta, "/start/theta_rad");
  appendExtra(start, map.start_extra);
  root["start"] = std::move(start);

  if (map.raster) {
    OrderedJson raster = OrderedJson::object();
    raster["source"] = raster_source;
    appendExtra(raster, map.raster->extra);
    root["raster"] = std::move(raster);
  }

  OrderedJson walls = OrderedJson::array();
  for (std::size_t i = 0; i < map.walls.size(); ++i) {
    const Wall& w = map.walls[i];
    OrderedJson o = OrderedJson::object();
    if (!w.id.empty())
      o["id"] = w.id;
    o["points"] = pointsJson(w.points, child(child("/walls", i), "points"));
    o["closed"] = w.closed;
    appendExtra(o, w.extra);
    walls.push_back(std::move(o));
  }
  root["walls"] = std::move(walls);

  OrderedJson obstacles = OrderedJson::array();
  for (std::size_t i = 0; i < map.obstacles.size(); ++i) {
    const Obstacle& ob = map.obstacles[i];
    OrderedJson o = OrderedJson::object();
    if (!ob.id.empty())
      o["id"] = ob.id;
    o["polygon"] = pointsJson(ob.polygon, child(child("/obstacles", i), "polygon"));
    appendExtra(o, ob.extra);
    obstacles.push_back(std::move(o));
  }
  root["obstacles"] = std::move(obstacles);

  OrderedJson features = OrderedJson::array();
  for (std::size_t i = 0; i < map.features.size(); ++i) {
    const PointFeature& f = map.features[i];
    OrderedJson o = OrderedJson::object();
    if (!f.id.empty())
      o["id"] = f.id;
    o["kind"] = f.kind == PointFeatureKind::kCorner ? "corner" : "edge";
    o["position"] = pointJson(f.position, child(child("/features", i), "position"));
    appendExtra(o, f.extra);
    features.push_back(std::move(o));
  }
  root["features"] = std::move(features);

  OrderedJson markers = OrderedJson::array();
  for (std::size_t i = 0; i < map.markers.size(); ++i) {
    const CeilingMarker& m = map.markers[i];
    const std::string p = child("/ceiling_markers", i);
    OrderedJson o = OrderedJson::object();
    if (!m.id.empty())
      o["id"] = m.id;
    o["position"] = pointJson(m.position, child(p, "position"));
    o["heading_rad"] = finite(m.heading_rad, child(p, "heading_rad"));
    o["size_m"] = finite(m.size_m, child(p, "size_m"));
    appendExtra(o, m.extra);
    markers.push_back(std::move(o));
  }
  root["ceiling_markers"] = std::move(markers);

  OrderedJson lights = OrderedJson::array();
  for (std::size_t i = 0; i < map.lights.size(); ++i) {
    const CeilingLight& l = map.lights[i];
    const std::string p = child("/ceiling_lights", i);
    OrderedJson o = OrderedJson::object();
    if (!l.id.empty())
      o["id"] = l.id;
    o["a"] = pointJson(l.tube.a, child(p, "a"));
    o["b"] = pointJson(l.tube.b, child(p, "b"));
    o["width_m"] = finite(l.width_m, child(p, "width_m"));
    appendExtra(o, l.extra);
    lights.push_back(std::move(o));
  }
  root["ceiling_lights"] = std::move(lights);

  OrderedJson graph = OrderedJson::object();
  OrderedJson nodes = OrderedJson::array();
  for (std::size_t i = 0; i < map.graph.nodes.size(); ++i) {
    const TopoNode& n = map.graph.nodes[i];
    OrderedJson o = OrderedJson::object();
    o["id"] = n.id;
    o["position"] = pointJson(n.position, child(child("/graph/nodes", i), "position"));
    if (!n.marker_id.empty())
      o["marker"] = n.marker_id;
    appendExtra(o, n.extra);
    nodes.push_back(std::move(o));
  }
  graph["nodes"] = std::move(nodes);
  OrderedJson edges = OrderedJson::array();
  for (const TopoEdge& e : map.graph.edges) {
    OrderedJson o = OrderedJson::object();
    o["from"] = e.from;
    o["to"] = e.to;
    o["bidirectional"] = e.bidirectional;
    appendExtra(o, e.extra);
    edges.push_back(std::move(o));
  }
  graph["edges"] = std::move(edges);
  appendExtra(graph, map.graph.extra);
  root["graph"] = std::move(graph);

  appendExtra(root, map.extra);
  return root;
}

// --- pretty printing -----------------------------------------------------------------------

constexpr std::size_t kLineWidth = 100;

std::string scalarText(const OrderedJson& v) {
  if (v.is_number_float() && !std::isfinite(v.get<double>()))
    throw std::invalid_argument("serializeMap: an unknown key holds a non-finite number");
  return v.dump(-1, ' ', false, OrderedJson::error_handler_t::replace);
}

std::string compactText(const OrderedJson& v) {
  if (!v.is_structured())
    return scalarText(v);
  std::string out(1, v.is_array() ? '[' : '{');
  bool first = true;
  for (auto it = v.begin(); it != v.end(); ++it) {
    if (!first)
      out += ", ";
    first = false;
    if (v.is_object())
      out += scalarText(OrderedJson(it.key())) + ": ";
    out += compactText(it.value());
  }
  out += v.is_array() ? ']' : '}';
  return out;
}

int nesting(const OrderedJson& v) {
  if (!v.is_structured())
    return 0;
  int deepest = 0;
  for (const auto& e : v)
    deepest = std::max(deepest, nesting(e));
  return deepest + 1;
}

bool holdsObject(const OrderedJson& v) {
  for (const auto& e : v) {
    if (e.is_object() || (e.is_array() && holdsObject(e)))
      return true;
  }
  return false;
}

// Writes v starting at column `column`, nested blocks indented by two spaces per level. Point
// lists ([[x, y], ...]) and objects without nested objects (a wall, a pose) stay on one line
// when they fit.
void prettyText(const OrderedJson& v, std::size_t indent, std::size_t column, std::string& out) {
  if (!v.is_structured() || v.empty()) {
    out += v.is_structured() ? (v.is_array() ? "[]" : "{}") : scalarText(v);
    return;
  }
  if (v.is_array() ? nesting(v) <= 2 : nesting(v) <= 3 && !holdsObject(v)) {
    const std::string c = compactText(v);
    if (column + c.size() + 1 <= kLineWidth) {
      out += c;
      return;
    }
  }
  const std::string pad(indent + 2, ' ');
  out += v.is_array() ? "[\n" : "{\n";
  bool first = true;
  for (auto it = v.begin(); it != v.end(); ++it) {
    if (!first)
      out += ",\n";
    first = false;
    out += pad;
    std::size_t at = pad.size();
    if (v.is_object()) {
      const std::string key = scalarText(OrderedJson(it.key())) + ": ";
      out += key;
      at += key.size();
    }
    prettyText(it.value(), indent + 2, at, out);
  }
  out += "\n" + std::string(indent, ' ') + (v.is_array() ? "]" : "}");
}

std::string render(const OrderedJson& root) {
  std::string out;
  prettyText(root, 0, 0, out);
  out += '\n';
  return out;
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

MapLoadResult loadMapFile(const fs::path& path) {
  const ReadFileResult file = readFile(path);
  if (!file.ok()) {
    MapLoadResult result;
    result.diagnostics.push_back({Severity::kError, path.string(), 0, 0, {}, file.error});
    return result;
  }
  return parseMapJson(file.bytes, path.string(), path.parent_path());
}

MapLoadResult loadAnyMap(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".json")
    return loadMapFile(path);
  MapLoadResult result;
  if (ext != ".yaml" && ext != ".yml") {
    result.diagnostics.push_back({Severity::kError,
                                  path.string(),
                                  0,
                                  0,
                                  {},
                                  "unknown map file type " +
                                      (ext.empty() ? std::string("(no extension)") : quote(ext)) +
                                      ": expected an IRGS map (.json) or a ROS map (.yaml)"});
    return result;
  }
  RosMapLoadResult ros = loadRosMap(path);
  result.diagnostics = std::move(ros.diagnostics);
  if (!ros.raster)
    return result;
  StartPoseSearch search;
  WorldMap world =
      worldFromRaster(std::move(*ros.raster), path.filename().string(), kStartClearance_m, &search);
  std::error_code ec;
  const fs::path absolute = fs::absolute(path, ec);
  world.raster->resolved_path = ec ? path.string() : absolute.lexically_normal().string();
  if (!search.found) {
    result.diagnostics.push_back(
        {Severity::kWarning,
         path.string(),
         0,
         0,
         {},
         "no free cell is at least 0.25 m from occupied or unknown cells; the start pose is the "
         "most open free cell found (clearance " +
             std::to_string(search.clearance_m) + " m)"});
  }
  result.map = std::move(world);
  return result;
}

std::string serializeMap(const WorldMap& map) {
  return render(toJson(map, map.raster ? map.raster->source : std::string()));
}

std::optional<std::string> saveMapFile(const WorldMap& map, const fs::path& path) {
  std::string source = map.raster ? map.raster->source : std::string();
  if (map.raster && !map.raster->resolved_path.empty()) {
    std::error_code ec;
    const fs::path folder = fs::absolute(path, ec).parent_path();
    const fs::path relative = fs::path(map.raster->resolved_path).lexically_relative(folder);
    source = ec || relative.empty() ? map.raster->resolved_path : relative.generic_string();
  }
  std::string text;
  try {
    text = render(toJson(map, source));
  } catch (const std::invalid_argument& e) {
    return "cannot save " + path.string() + ": " + e.what();
  }
  return writeFileAtomically(path, text);
}

}  // namespace irgs
