// Writing: WorldMap -> map JSON text (fixed key order, unknown keys kept), and the atomic save.
#include "core/world/map_file.hpp"

#include <cmath>
#include <stdexcept>

#include "core/io/atomic_file.hpp"
#include "core/world/map_file_internal.hpp"
#include "core/world/map_json_layout.hpp"

namespace irgs {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using OrderedJson = nlohmann::ordered_json;
using map_file_internal::child;

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

OrderedJson toJson(const WorldMap& map, const std::string& raster_source,
                   const std::string& plan_source) {
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

  if (map.floor_plan) {  // written only when present, so maps without it keep their bytes
    const FloorPlan& f = *map.floor_plan;
    OrderedJson plan = OrderedJson::object();
    plan["source"] = plan_source;
    plan["metres_per_pixel"] = finite(f.metres_per_pixel, "/floor_plan/metres_per_pixel");
    plan["origin"] = pointJson(f.origin, "/floor_plan/origin");
    plan["rotation_rad"] = finite(f.rotation_rad, "/floor_plan/rotation_rad");
    plan["opacity"] = finite(f.opacity, "/floor_plan/opacity");
    appendExtra(plan, f.extra);
    root["floor_plan"] = std::move(plan);
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
    if (!(m.colour == kDefaultMarkerColour))  // maps without colours keep their bytes
      o["colour"] = formatHexColour(m.colour);
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
  for (std::size_t i = 0; i < map.graph.edges.size(); ++i) {
    const TopoEdge& e = map.graph.edges[i];
    OrderedJson o = OrderedJson::object();
    o["from"] = e.from;
    o["to"] = e.to;
    o["bidirectional"] = e.bidirectional;
    if (e.cost_m)
      o["cost_m"] = finite(*e.cost_m, child(child("/graph/edges", i), "cost_m"));
    appendExtra(o, e.extra);
    edges.push_back(std::move(o));
  }
  graph["edges"] = std::move(edges);
  appendExtra(graph, map.graph.extra);
  root["graph"] = std::move(graph);

  // Optional layer: written only when present, so maps without it keep their bytes.
  if (!map.moving_obstacles.empty()) {
    OrderedJson movers = OrderedJson::array();
    for (std::size_t i = 0; i < map.moving_obstacles.size(); ++i) {
      const MovingObstacle& m = map.moving_obstacles[i];
      const std::string p = child("/moving_obstacles", i);
      OrderedJson o = OrderedJson::object();
      if (!m.id.empty())
        o["id"] = m.id;
      o["polygon"] = pointsJson(m.polygon, child(p, "polygon"));
      o["path"] = pointsJson(m.path, child(p, "path"));
      o["speed_mps"] = finite(m.speed_mps, child(p, "speed_mps"));
      o["loop"] = m.loop;
      o["start_delay_s"] = finite(m.start_delay_s, child(p, "start_delay_s"));
      appendExtra(o, m.extra);
      movers.push_back(std::move(o));
    }
    root["moving_obstacles"] = std::move(movers);
  }

  appendExtra(root, map.extra);
  return root;
}

}  // namespace

std::string serializeMap(const WorldMap& map) {
  return map_file_internal::layoutJson(
      toJson(map, map.raster ? map.raster->source : std::string(),
             map.floor_plan ? map.floor_plan->source : std::string()));
}

std::optional<std::string> saveMapFile(const WorldMap& map, const fs::path& path) {
  // Referenced files (raster YAML, floor-plan image) are written relative to the map's folder.
  std::error_code ec;
  const fs::path folder = fs::absolute(path, ec).parent_path();
  auto reference = [&](const std::string& source, const std::string& resolved) {
    if (resolved.empty())
      return source;
    const fs::path relative = fs::path(resolved).lexically_relative(folder);
    return ec || relative.empty() ? resolved : relative.generic_string();
  };
  const std::string source =
      map.raster ? reference(map.raster->source, map.raster->resolved_path) : std::string();
  const std::string plan_source =
      map.floor_plan ? reference(map.floor_plan->source, map.floor_plan->resolved_path)
                     : std::string();
  std::string text;
  try {
    text = map_file_internal::layoutJson(toJson(map, source, plan_source));
  } catch (const std::invalid_argument& e) {
    return "cannot save " + path.string() + ": " + e.what();
  }
  return writeFileAtomically(path, text);
}

}  // namespace irgs
