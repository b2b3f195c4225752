#include "core/editing/map_edit.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <stdexcept>
#include <unordered_set>

#include "core/editing/edit_geometry.hpp"

namespace irgs::editing {
namespace {

template <class... Ts>
struct Overloaded : Ts... {
  using Ts::operator()...;
};

bool finite(const Vec2& p) {
  return std::isfinite(p.x()) && std::isfinite(p.y());
}

Vec2 rotatePoint(const Vec2& p, double angle_rad, const Vec2& pivot) {
  const double c = std::cos(angle_rad), s = std::sin(angle_rad);
  const Vec2 d = p - pivot;
  return pivot + Vec2(c * d.x() - s * d.y(), s * d.x() + c * d.y());
}

const char* kindName(ElementKind kind) {
  switch (kind) {
    case ElementKind::kWall:
      return "wall";
    case ElementKind::kObstacle:
      return "obstacle";
    case ElementKind::kFeature:
      return "feature";
    case ElementKind::kStart:
      return "start pose";
    case ElementKind::kMarker:
      return "marker";
    case ElementKind::kLight:
      return "light";
    case ElementKind::kNode:
      return "node";
    case ElementKind::kEdge:
      return "edge";
  }
  return "element";
}

constexpr std::size_t kKindCount = 8;

std::size_t countOf(const WorldMap& map, ElementKind kind) {
  switch (kind) {
    case ElementKind::kWall:
      return map.walls.size();
    case ElementKind::kObstacle:
      return map.obstacles.size();
    case ElementKind::kFeature:
      return map.features.size();
    case ElementKind::kStart:
      return 1;
    case ElementKind::kMarker:
      return map.markers.size();
    case ElementKind::kLight:
      return map.lights.size();
    case ElementKind::kNode:
      return map.graph.nodes.size();
    case ElementKind::kEdge:
      return map.graph.edges.size();
  }
  return 0;
}

// Throws std::invalid_argument for an element that cannot be part of a map.
void checkElement(const Element& element) {
  std::visit(Overloaded{
                 [](const Wall& w) {
                   if (w.points.size() < 2)
                     throw std::invalid_argument("a wall needs at least two points");
                   for (const Vec2& p : w.points)
                     if (!finite(p))
                       throw std::invalid_argument("wall point is not finite");
                 },
                 [](const Obstacle& o) {
                   if (o.polygon.size() < 3)
                     throw std::invalid_argument("an obstacle needs at least three vertices");
                   for (const Vec2& p : o.polygon)
                     if (!finite(p))
                       throw std::invalid_argument("obstacle vertex is not finite");
                 },
                 [](const PointFeature& f) {
                   if (!finite(f.position))
                     throw std::invalid_argument("feature position is not finite");
                 },
                 [](const Pose2& p) {
                   if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.theta))
                     throw std::invalid_argument("start pose is not finite");
                 },
                 [](const CeilingMarker& m) {
                   if (!finite(m.position) || !std::isfinite(m.heading_rad))
                     throw std::invalid_argument("marker pose is not finite");
                   if (!(std::isfinite(m.size_m) && m.size_m > 0.0))
                     throw std::invalid_argument("a marker's size must be > 0 m");
                   for (int c : {m.colour.r, m.colour.g, m.colour.b})
                     if (c < 0 || c > 255)
                       throw std::invalid_argument("a marker's colour channels are 0..255");
                 },
                 [](const CeilingLight& l) {
                   if (!finite(l.tube.a) || !finite(l.tube.b))
                     throw std::invalid_argument("light end is not finite");
                   if (!((l.tube.b - l.tube.a).norm() > 0.0))
                     throw std::invalid_argument("a light needs two different ends");
                   if (!(std::isfinite(l.width_m) && l.width_m > 0.0))
                     throw std::invalid_argument("a light's width must be > 0 m");
                 },
                 [](const TopoNode& n) {
                   if (!finite(n.position))
                     throw std::invalid_argument("node position is not finite");
                 },
                 [](const TopoEdge& e) {
                   if (e.from.empty() || e.to.empty())
                     throw std::invalid_argument("an edge needs two node ids");
                   if (e.from == e.to)
                     throw std::invalid_argument("an edge must join two different nodes");
                   if (e.cost_m && !(std::isfinite(*e.cost_m) && *e.cost_m > 0.0))
                     throw std::invalid_argument("an edge's given cost must be > 0 m");
                 },
             },
             element);
}

bool hasMarker(const WorldMap& map, const std::string& id) {
  return std::any_of(map.markers.begin(), map.markers.end(),
                     [&](const CeilingMarker& m) { return m.id == id; });
}

// Checks of an element against the rest of the map (`skip`: the edge being replaced).
void checkReferences(const WorldMap& map, const Element& element,
                     std::optional<std::size_t> skip = std::nullopt) {
  if (const auto* n = std::get_if<TopoNode>(&element)) {
    if (!n->marker_id.empty() && !hasMarker(map, n->marker_id))
      throw std::invalid_argument("node is tied to the unknown marker '" + n->marker_id + "'");
  } else if (const auto* e = std::get_if<TopoEdge>(&element)) {
    for (const std::string* id : {&e->from, &e->to})
      if (map.graph.node(*id) == nullptr)
        throw std::invalid_argument("edge names the unknown node '" + *id + "'");
    for (std::size_t i = 0; i < map.graph.edges.size(); ++i) {
      const TopoEdge& o = map.graph.edges[i];
      if (skip && *skip == i)
        continue;
      if ((o.from == e->from && o.to == e->to) || (o.from == e->to && o.to == e->from))
        throw std::invalid_argument("nodes '" + e->from + "' and '" + e->to +
                                    "' are already joined by an edge");
    }
  }
}

void setId(Element& element, std::string id) {
  std::visit(Overloaded{[](Pose2&) {}, [](TopoEdge&) {}, [&](auto& e) { e.id = std::move(id); }},
             element);
}

// Obstacles are stored counter-clockwise (as the loader does); the start heading is wrapped.
Element normalised(Element element) {
  if (auto* o = std::get_if<Obstacle>(&element)) {
    if (signedArea2(o->polygon) < 0.0)
      std::reverse(o->polygon.begin(), o->polygon.end());
  } else if (auto* p = std::get_if<Pose2>(&element)) {
    p->theta = wrapAngle(p->theta);
  } else if (auto* m = std::get_if<CeilingMarker>(&element)) {
    m->heading_rad = wrapAngle(m->heading_rad);
  }
  return element;
}

// Ids in the group of `kind` (see the header): walls, obstacles and features share one.
std::unordered_set<std::string> usedIds(const WorldMap& map,
                                        ElementKind kind = ElementKind::kWall) {
  std::unordered_set<std::string> ids;
  switch (kind) {
    case ElementKind::kMarker:
      for (const CeilingMarker& m : map.markers)
        ids.insert(m.id);
      break;
    case ElementKind::kLight:
      for (const CeilingLight& l : map.lights)
        ids.insert(l.id);
      break;
    case ElementKind::kNode:
      for (const TopoNode& n : map.graph.nodes)
        ids.insert(n.id);
      break;
    default:
      for (const Wall& w : map.walls)
        ids.insert(w.id);
      for (const Obstacle& o : map.obstacles)
        ids.insert(o.id);
      for (const PointFeature& f : map.features)
        ids.insert(f.id);
      break;
  }
  return ids;
}

bool hasId(ElementKind kind) {
  return kind != ElementKind::kStart && kind != ElementKind::kEdge;
}

std::string freshId(std::unordered_set<std::string>& used, std::string_view prefix) {
  for (std::size_t n = 1;; ++n) {
    std::string id = std::string(prefix) + "-" + std::to_string(n);
    if (used.insert(id).second)
      return id;
  }
}

std::string_view idPrefix(ElementKind kind) {
  switch (kind) {
    case ElementKind::kWall:
      return "wall";
    case ElementKind::kObstacle:
      return "obstacle";
    case ElementKind::kFeature:
      return "feature";
    case ElementKind::kStart:
      return "start";
    case ElementKind::kMarker:
      return "marker";
    case ElementKind::kLight:
      return "light";
    case ElementKind::kNode:
      return "node";
    case ElementKind::kEdge:
      return "edge";
  }
  return "element";
}

// --- Raw vector operations, checked -------------------------------------------------------------

template <class T>
void insertAt(std::vector<T>& v, std::size_t index, const Element& e) {
  if (index > v.size())
    throw std::logic_error("edit does not fit the map: insertion index out of range");
  v.insert(v.begin() + static_cast<std::ptrdiff_t>(index), std::get<T>(e));
}
template <class T>
void replaceAt(std::vector<T>& v, std::size_t index, const Element& e) {
  if (index >= v.size())
    throw std::logic_error("edit does not fit the map: index out of range");
  v[index] = std::get<T>(e);
}
template <class T>
void eraseAt(std::vector<T>& v, std::size_t index) {
  if (index >= v.size())
    throw std::logic_error("edit does not fit the map: erase index out of range");
  v.erase(v.begin() + static_cast<std::ptrdiff_t>(index));
}

template <class T>
void performOn(std::vector<T>& v, std::size_t index, const std::optional<Element>& from,
               const std::optional<Element>& to) {
  if (from && to)
    replaceAt(v, index, *to);
  else if (to)
    insertAt(v, index, *to);
  else if (from)
    eraseAt(v, index);
}

// Turns `from` into `to` at the change's place.
void perform(WorldMap& map, const Change& change, const std::optional<Element>& from,
             const std::optional<Element>& to) {
  if ((from && kindOf(*from) != change.kind) || (to && kindOf(*to) != change.kind))
    throw std::logic_error("edit does not fit the map: element kind mismatch");
  switch (change.kind) {
    case ElementKind::kWall:
      performOn(map.walls, change.index, from, to);
      break;
    case ElementKind::kObstacle:
      performOn(map.obstacles, change.index, from, to);
      break;
    case ElementKind::kFeature:
      performOn(map.features, change.index, from, to);
      break;
    case ElementKind::kStart:
      if (!from || !to)
        throw std::logic_error("the start pose can only be replaced");
      map.start = std::get<Pose2>(*to);
      break;
    case ElementKind::kMarker:
      performOn(map.markers, change.index, from, to);
      break;
    case ElementKind::kLight:
      performOn(map.lights, change.index, from, to);
      break;
    case ElementKind::kNode:
      performOn(map.graph.nodes, change.index, from, to);
      break;
    case ElementKind::kEdge:
      performOn(map.graph.edges, change.index, from, to);
      break;
  }
}

// Sorted, unique, valid refs.
std::vector<ElementRef> cleanRefs(const WorldMap& map, const std::vector<ElementRef>& refs) {
  std::set<ElementRef> unique;
  for (const ElementRef& r : refs) {
    if (!isValidRef(map, r))
      throw std::out_of_range(std::string("no such ") + kindName(r.kind) + " #" +
                              std::to_string(r.index));
    unique.insert(r);
  }
  return {unique.begin(), unique.end()};
}

// Nodes that go along when the referenced elements move or rotate (and are not referenced
// themselves): those tied to a referenced marker, and the ends of a referenced edge (an edge has
// no points of its own: moving it moves its nodes).
std::vector<ElementRef> tiedNodes(const WorldMap& map, const std::vector<ElementRef>& refs) {
  std::set<std::string> markers, ends;
  for (const ElementRef& r : refs) {
    if (r.kind == ElementKind::kMarker) {
      markers.insert(map.markers[r.index].id);
    } else if (r.kind == ElementKind::kEdge) {
      ends.insert(map.graph.edges[r.index].from);
      ends.insert(map.graph.edges[r.index].to);
    }
  }
  std::vector<ElementRef> out;
  for (std::size_t i = 0; i < map.graph.nodes.size(); ++i) {
    const ElementRef ref{ElementKind::kNode, i};
    const TopoNode& n = map.graph.nodes[i];
    const bool tied = !n.marker_id.empty() && markers.count(n.marker_id) > 0;
    if ((tied || ends.count(n.id) > 0) && std::find(refs.begin(), refs.end(), ref) == refs.end())
      out.push_back(ref);
  }
  return out;
}

template <class F>
Edit transformEach(const WorldMap& map, const std::vector<ElementRef>& refs, std::string label,
                   F transform) {
  Edit edit;
  edit.label = std::move(label);
  const std::vector<ElementRef> clean = cleanRefs(map, refs);
  std::vector<ElementRef> all = clean;
  for (const ElementRef& r : tiedNodes(map, clean))
    all.push_back(r);
  for (const ElementRef& r : all) {
    Element before = elementAt(map, r);
    Element after = normalised(transform(before));
    checkElement(after);
    edit.changes.push_back({r.kind, r.index, std::move(before), std::move(after)});
  }
  edit.selection_after = clean;
  return edit;
}

}  // namespace

ElementKind kindOf(const Element& element) {
  return std::visit(Overloaded{[](const Wall&) { return ElementKind::kWall; },
                               [](const Obstacle&) { return ElementKind::kObstacle; },
                               [](const PointFeature&) { return ElementKind::kFeature; },
                               [](const Pose2&) { return ElementKind::kStart; },
                               [](const CeilingMarker&) { return ElementKind::kMarker; },
                               [](const CeilingLight&) { return ElementKind::kLight; },
                               [](const TopoNode&) { return ElementKind::kNode; },
                               [](const TopoEdge&) { return ElementKind::kEdge; }},
                    element);
}

bool isValidRef(const WorldMap& map, const ElementRef& ref) {
  return ref.kind == ElementKind::kStart ? ref.index == 0 : ref.index < countOf(map, ref.kind);
}

Element elementAt(const WorldMap& map, const ElementRef& ref) {
  if (!isValidRef(map, ref))
    throw std::out_of_range(std::string("no such ") + kindName(ref.kind) + " #" +
                            std::to_string(ref.index));
  switch (ref.kind) {
    case ElementKind::kWall:
      return map.walls[ref.index];
    case ElementKind::kObstacle:
      return map.obstacles[ref.index];
    case ElementKind::kFeature:
      return map.features[ref.index];
    case ElementKind::kStart:
      break;
    case ElementKind::kMarker:
      return map.markers[ref.index];
    case ElementKind::kLight:
      return map.lights[ref.index];
    case ElementKind::kNode:
      return map.graph.nodes[ref.index];
    case ElementKind::kEdge:
      return map.graph.edges[ref.index];
  }
  return map.start;
}

std::string elementId(const Element& element) {
  return std::visit(
      Overloaded{[](const Pose2&) { return std::string(); },
                 [](const TopoEdge&) { return std::string(); }, [](const auto& e) { return e.id; }},
      element);
}

std::string describe(const Element& element) {
  const ElementKind kind = kindOf(element);
  if (kind == ElementKind::kStart)
    return kindName(kind);
  if (const auto* e = std::get_if<TopoEdge>(&element))
    return "edge '" + e->from + "' " + (e->bidirectional ? "-" : "->") + " '" + e->to + "'";
  return std::string(kindName(kind)) + " '" + elementId(element) + "'";
}

Box2 elementBounds(const Element& element) {
  Box2 box;
  std::visit(Overloaded{[&](const Wall& w) {
                          for (const Vec2& p : w.points)
                            box.extend(p);
                        },
                        [&](const Obstacle& o) {
                          for (const Vec2& p : o.polygon)
                            box.extend(p);
                        },
                        [&](const PointFeature& f) { box.extend(f.position); },
                        [&](const Pose2& p) { box.extend(p.position()); },
                        [&](const CeilingMarker& m) { box.extend(m.position); },
                        [&](const CeilingLight& l) {
                          box.extend(l.tube.a);
                          box.extend(l.tube.b);
                        },
                        [&](const TopoNode& n) { box.extend(n.position); }, [](const TopoEdge&) {}},
             element);
  return box;
}

std::vector<Vec2> elementPoints(const WorldMap& map, const Element& element) {
  return std::visit(Overloaded{[](const Wall& w) { return w.points; },
                               [](const Obstacle& o) { return o.polygon; },
                               [](const PointFeature& f) { return std::vector<Vec2>{f.position}; },
                               [](const Pose2& p) { return std::vector<Vec2>{p.position()}; },
                               [](const CeilingMarker& m) { return std::vector<Vec2>{m.position}; },
                               [](const CeilingLight& l) {
                                 return std::vector<Vec2>{l.tube.a, l.tube.b};
                               },
                               [](const TopoNode& n) { return std::vector<Vec2>{n.position}; },
                               [&](const TopoEdge& e) {
                                 std::vector<Vec2> out;
                                 for (const std::string* id : {&e.from, &e.to})
                                   if (const TopoNode* n = map.graph.node(*id))
                                     out.push_back(n->position);
                                 return out;
                               }},
                    element);
}

Element translated(const Element& element, const Vec2& delta) {
  Element out = element;
  std::visit(Overloaded{[&](Wall& w) {
                          for (Vec2& p : w.points)
                            p += delta;
                        },
                        [&](Obstacle& o) {
                          for (Vec2& p : o.polygon)
                            p += delta;
                        },
                        [&](PointFeature& f) { f.position += delta; },
                        [&](Pose2& p) {
                          p.x += delta.x();
                          p.y += delta.y();
                        },
                        [&](CeilingMarker& m) { m.position += delta; },
                        [&](CeilingLight& l) {
                          l.tube.a += delta;
                          l.tube.b += delta;
                        },
                        [&](TopoNode& n) { n.position += delta; }, [](TopoEdge&) {}},
             out);
  return out;
}

Element rotated(const Element& element, double angle_rad, const Vec2& pivot) {
  Element out = element;
  std::visit(
      Overloaded{[&](Wall& w) {
                   for (Vec2& p : w.points)
                     p = rotatePoint(p, angle_rad, pivot);
                 },
                 [&](Obstacle& o) {
                   for (Vec2& p : o.polygon)
                     p = rotatePoint(p, angle_rad, pivot);
                 },
                 [&](PointFeature& f) { f.position = rotatePoint(f.position, angle_rad, pivot); },
                 [&](Pose2& p) {
                   const Vec2 q = rotatePoint(p.position(), angle_rad, pivot);
                   p = Pose2{q.x(), q.y(), wrapAngle(p.theta + angle_rad)};
                 },
                 [&](CeilingMarker& m) {
                   m.position = rotatePoint(m.position, angle_rad, pivot);
                   m.heading_rad = wrapAngle(m.heading_rad + angle_rad);
                 },
                 [&](CeilingLight& l) {
                   l.tube.a = rotatePoint(l.tube.a, angle_rad, pivot);
                   l.tube.b = rotatePoint(l.tube.b, angle_rad, pivot);
                 },
                 [&](TopoNode& n) { n.position = rotatePoint(n.position, angle_rad, pivot); },
                 [](TopoEdge&) {}},
      out);
  return out;
}

void applyEdit(WorldMap& map, const Edit& edit) {
  std::size_t done = 0;
  try {
    for (; done < edit.changes.size(); ++done) {
      const Change& c = edit.changes[done];
      perform(map, c, c.before, c.after);
    }
  } catch (...) {
    // Undo what was done so the map is unchanged, then report the misuse.
    while (done > 0) {
      --done;
      const Change& c = edit.changes[done];
      perform(map, c, c.after, c.before);
    }
    throw;
  }
  if (edit.raster)
    map.raster = edit.raster->after;
  if (edit.floor_plan)
    map.floor_plan = edit.floor_plan->after;
}

void revertEdit(WorldMap& map, const Edit& edit) {
  std::size_t left = edit.changes.size();
  try {
    for (; left > 0; --left) {
      const Change& c = edit.changes[left - 1];
      perform(map, c, c.after, c.before);
    }
  } catch (...) {
    for (; left < edit.changes.size(); ++left) {
      const Change& c = edit.changes[left];
      perform(map, c, c.before, c.after);
    }
    throw;
  }  // The raster layer is independent of the elements: its order among the changes is free.
  if (edit.raster)
    map.raster = edit.raster->before;
  if (edit.floor_plan)
    map.floor_plan = edit.floor_plan->before;
}

Edit setFloorPlan(const WorldMap& map, std::optional<FloorPlan> plan, std::string label) {
  if (plan) {
    if (plan->source.empty())
      throw std::invalid_argument("floor plan: no image file");
    if (!(std::isfinite(plan->metres_per_pixel) && plan->metres_per_pixel > 0.0))
      throw std::invalid_argument("floor plan: the scale must be > 0 m per pixel");
    if (!finite(plan->origin) || !std::isfinite(plan->rotation_rad))
      throw std::invalid_argument("floor plan: origin or rotation is not finite");
    if (!(plan->opacity >= 0.0 && plan->opacity <= 1.0))
      throw std::invalid_argument("floor plan: the opacity must be from 0 to 1");
    plan->rotation_rad = wrapAngle(plan->rotation_rad);
  }
  Edit edit;
  edit.label = plan ? std::move(label) : "Remove floor plan";
  edit.floor_plan = FloorPlanChange{map.floor_plan, std::move(plan)};
  return edit;
}

Edit setRasterLayer(const WorldMap& map, std::optional<RasterLayer> layer) {
  if (layer) {
    const RasterMap& r = layer->raster;
    if (r.width <= 0 || r.height <= 0 ||
        r.cells.size() != static_cast<std::size_t>(r.width) * static_cast<std::size_t>(r.height))
      throw std::invalid_argument("raster layer: cell count does not match its size");
    if (!(std::isfinite(r.resolution_m) && r.resolution_m > 0.0))
      throw std::invalid_argument("raster layer: resolution must be > 0");
  }
  Edit edit;
  edit.label = layer ? "Import raster layer" : "Remove raster layer";
  edit.raster = RasterChange{map.raster, std::move(layer)};
  edit.selection_after = {};
  return edit;
}

std::string uniqueId(const WorldMap& map, std::string_view prefix) {
  std::unordered_set<std::string> used = usedIds(map);
  return freshId(used, prefix);
}

Edit addElement(const WorldMap& map, Element element) {
  checkElement(element);
  const ElementKind kind = kindOf(element);
  if (kind == ElementKind::kStart)
    return setStart(map, std::get<Pose2>(element));
  std::unordered_set<std::string> used = usedIds(map, kind);
  const std::string id = elementId(element);
  if (hasId(kind) && (id.empty() || used.count(id) > 0))
    setId(element, freshId(used, idPrefix(kind)));
  checkReferences(map, element);
  Edit edit;
  edit.label = std::string("Add ") + kindName(kind);
  const std::size_t index = countOf(map, kind);
  edit.changes.push_back({kind, index, std::nullopt, normalised(std::move(element))});
  edit.selection_after.push_back({kind, index});
  return edit;
}

Edit setStart(const WorldMap& map, const Pose2& start) {
  checkElement(start);
  Edit edit;
  edit.label = "Set start pose";
  edit.changes.push_back({ElementKind::kStart, 0, Element(map.start),
                          Element(Pose2{start.x, start.y, wrapAngle(start.theta)})});
  edit.selection_after.push_back({ElementKind::kStart, 0});
  return edit;
}

Edit replaceElement(const WorldMap& map, const ElementRef& ref, Element element,
                    std::string label) {
  Element before = elementAt(map, ref);
  if (kindOf(element) != ref.kind)
    throw std::invalid_argument("replaceElement: the new element is of another kind");
  checkElement(element);
  const std::string id = elementId(element);
  const std::string old_id = elementId(before);
  const bool renamed = hasId(ref.kind) && id != old_id;
  if (renamed && (id.empty() || usedIds(map, ref.kind).count(id) > 0))
    throw std::invalid_argument("id '" + id + "' is empty or already used");
  checkReferences(
      map, element,
      ref.kind == ElementKind::kEdge ? std::optional<std::size_t>(ref.index) : std::nullopt);
  Edit edit;
  edit.label = std::move(label);
  edit.changes.push_back({ref.kind, ref.index, std::move(before), normalised(std::move(element))});
  edit.selection_after.push_back(ref);
  // References follow a renamed marker (the nodes tied to it) or node (its edges); the nodes
  // tied to a marker also follow its new position.
  if (ref.kind == ElementKind::kMarker && !old_id.empty()) {
    const Vec2 shift = std::get<CeilingMarker>(edit.changes.front().after.value()).position -
                       std::get<CeilingMarker>(edit.changes.front().before.value()).position;
    for (std::size_t i = 0; i < map.graph.nodes.size(); ++i) {
      if (map.graph.nodes[i].marker_id != old_id || (!renamed && shift.norm() == 0.0))
        continue;
      TopoNode n = map.graph.nodes[i];
      n.marker_id = id;
      n.position += shift;
      edit.changes.push_back({ElementKind::kNode, i, Element(map.graph.nodes[i]), Element(n)});
    }
  } else if (renamed && ref.kind == ElementKind::kNode) {
    for (std::size_t i = 0; i < map.graph.edges.size(); ++i) {
      TopoEdge e = map.graph.edges[i];
      if (e.from != old_id && e.to != old_id)
        continue;
      if (e.from == old_id)
        e.from = id;
      if (e.to == old_id)
        e.to = id;
      edit.changes.push_back({ElementKind::kEdge, i, Element(map.graph.edges[i]), Element(e)});
    }
  }
  return edit;
}

Edit moveVertex(const WorldMap& map, const ElementRef& ref, std::size_t vertex, const Vec2& to) {
  Element element = elementAt(map, ref);
  std::vector<Vec2>* points = nullptr;
  if (auto* w = std::get_if<Wall>(&element))
    points = &w->points;
  else if (auto* o = std::get_if<Obstacle>(&element))
    points = &o->polygon;
  if (auto* l = std::get_if<CeilingLight>(&element)) {
    if (vertex > 1)
      throw std::out_of_range("moveVertex: a light has two ends");
    (vertex == 0 ? l->tube.a : l->tube.b) = to;
    return replaceElement(map, ref, std::move(element), "Move light end");
  }
  if (points == nullptr || vertex >= points->size())
    throw std::out_of_range("moveVertex: no such vertex");
  (*points)[vertex] = to;
  return replaceElement(map, ref, std::move(element), "Move vertex");
}

Edit moveElements(const WorldMap& map, const std::vector<ElementRef>& refs, const Vec2& delta) {
  if (!finite(delta))
    throw std::invalid_argument("moveElements: delta is not finite");
  return transformEach(map, refs, "Move", [&](const Element& e) { return translated(e, delta); });
}

Edit rotateElements(const WorldMap& map, const std::vector<ElementRef>& refs, double angle_rad,
                    const Vec2& pivot) {
  if (!std::isfinite(angle_rad) || !finite(pivot))
    throw std::invalid_argument("rotateElements: angle or pivot is not finite");
  return transformEach(map, refs, "Rotate",
                       [&](const Element& e) { return rotated(e, angle_rad, pivot); });
}

Edit deleteElements(const WorldMap& map, const std::vector<ElementRef>& refs) {
  std::set<ElementRef> doomed;
  for (const ElementRef& r : cleanRefs(map, refs))
    if (r.kind != ElementKind::kStart)
      doomed.insert(r);
  // A deleted node takes its edges along.
  std::set<std::string> nodes, markers;
  for (const ElementRef& r : doomed) {
    if (r.kind == ElementKind::kNode)
      nodes.insert(map.graph.nodes[r.index].id);
    else if (r.kind == ElementKind::kMarker)
      markers.insert(map.markers[r.index].id);
  }
  for (std::size_t i = 0; i < map.graph.edges.size(); ++i) {
    const TopoEdge& e = map.graph.edges[i];
    if (nodes.count(e.from) > 0 || nodes.count(e.to) > 0)
      doomed.insert({ElementKind::kEdge, i});
  }
  Edit edit;
  edit.label = "Delete";
  // Untie the surviving nodes of deleted markers first, while every index is the original one.
  for (std::size_t i = 0; i < map.graph.nodes.size(); ++i) {
    const TopoNode& n = map.graph.nodes[i];
    if (n.marker_id.empty() || markers.count(n.marker_id) == 0 ||
        doomed.count({ElementKind::kNode, i}) > 0)
      continue;
    TopoNode untied = n;
    untied.marker_id.clear();
    edit.changes.push_back({ElementKind::kNode, i, Element(n), Element(untied)});
  }
  // Highest index first within each kind, so earlier erasures do not shift later ones.
  for (auto it = doomed.rbegin(); it != doomed.rend(); ++it)
    edit.changes.push_back({it->kind, it->index, elementAt(map, *it), std::nullopt});
  return edit;
}

Clipboard copyElements(const WorldMap& map, const std::vector<ElementRef>& refs) {
  Clipboard out;
  std::set<std::string> nodes;
  for (const ElementRef& r : cleanRefs(map, refs)) {
    if (r.kind == ElementKind::kNode)
      nodes.insert(map.graph.nodes[r.index].id);
    if (r.kind == ElementKind::kEdge) {
      const TopoEdge& e = map.graph.edges[r.index];
      if (nodes.count(e.from) == 0 || nodes.count(e.to) == 0)
        continue;  // kinds are in order: the nodes came first
    }
    if (r.kind != ElementKind::kStart)
      out.push_back(elementAt(map, r));
  }
  return out;
}

Edit pasteElements(const WorldMap& map, const Clipboard& clipboard, const Vec2& offset) {
  if (!finite(offset))
    throw std::invalid_argument("pasteElements: offset is not finite");
  std::unordered_set<std::string> used[kKindCount];
  std::size_t next[kKindCount];
  for (std::size_t k = 0; k < kKindCount; ++k) {
    const auto kind = static_cast<ElementKind>(k);
    // The group of walls, obstacles and features is one set: slot 0 stands for all three.
    used[k] = usedIds(map, kind);
    next[k] = countOf(map, kind);
  }
  auto group = [](ElementKind kind) {
    return kind == ElementKind::kObstacle || kind == ElementKind::kFeature
               ? std::size_t{0}
               : static_cast<std::size_t>(kind);
  };
  std::map<std::string, std::string> marker_ids, node_ids;  // copied id -> pasted id
  Edit edit;
  edit.label = "Paste";
  for (const Element& source : clipboard) {
    const ElementKind kind = kindOf(source);
    if (kind == ElementKind::kStart)
      continue;
    Element e = normalised(translated(source, offset));
    checkElement(e);
    if (hasId(kind)) {
      const std::string fresh = freshId(used[group(kind)], idPrefix(kind));
      if (kind == ElementKind::kMarker)
        marker_ids[elementId(source)] = fresh;
      else if (kind == ElementKind::kNode)
        node_ids[elementId(source)] = fresh;
      setId(e, fresh);
    }
    if (auto* n = std::get_if<TopoNode>(&e)) {
      const auto tie = marker_ids.find(n->marker_id);
      n->marker_id = tie == marker_ids.end() ? std::string() : tie->second;
    } else if (auto* ed = std::get_if<TopoEdge>(&e)) {
      const auto a = node_ids.find(ed->from), b = node_ids.find(ed->to);
      if (a == node_ids.end() || b == node_ids.end())
        continue;  // an edge is pasted only with both of its nodes
      ed->from = a->second;
      ed->to = b->second;
    }
    const std::size_t index = next[static_cast<std::size_t>(kind)]++;
    edit.changes.push_back({kind, index, std::nullopt, std::move(e)});
    edit.selection_after.push_back({kind, index});
  }
  return edit;
}

Edit replaceContents(const WorldMap& current, const WorldMap& target, std::string label) {
  Edit edit;
  edit.label = std::move(label);
  auto replaceKind = [&](ElementKind kind, const auto& from, const auto& to) {
    for (std::size_t i = from.size(); i > 0; --i)
      edit.changes.push_back({kind, i - 1, Element(from[i - 1]), std::nullopt});
    for (std::size_t i = 0; i < to.size(); ++i)
      edit.changes.push_back({kind, i, std::nullopt, Element(to[i])});
  };
  replaceKind(ElementKind::kWall, current.walls, target.walls);
  replaceKind(ElementKind::kObstacle, current.obstacles, target.obstacles);
  replaceKind(ElementKind::kFeature, current.features, target.features);
  replaceKind(ElementKind::kEdge, current.graph.edges, target.graph.edges);
  replaceKind(ElementKind::kNode, current.graph.nodes, target.graph.nodes);
  replaceKind(ElementKind::kMarker, current.markers, target.markers);
  replaceKind(ElementKind::kLight, current.lights, target.lights);
  if (!(current.start == target.start))
    edit.changes.push_back({ElementKind::kStart, 0, Element(current.start), Element(target.start)});
  // The layers under the map too (a recovery restores an imported raster or a calibrated plan).
  // A raster is compared by the file it came from: its cells are that file's.
  const auto rasterFile = [](const std::optional<RasterLayer>& r) {
    return r ? std::optional<std::string>(r->resolved_path.empty() ? r->source : r->resolved_path)
             : std::nullopt;
  };
  if (rasterFile(current.raster) != rasterFile(target.raster))
    edit.raster = RasterChange{current.raster, target.raster};
  if (current.floor_plan != target.floor_plan)
    edit.floor_plan = FloorPlanChange{current.floor_plan, target.floor_plan};
  return edit;
}

Vec2 selectionCentre(const WorldMap& map, const std::vector<ElementRef>& refs) {
  Box2 box;
  for (const ElementRef& r : refs) {
    if (isValidRef(map, r))
      for (const Vec2& p : elementPoints(map, elementAt(map, r)))
        box.extend(p);
  }
  return box.empty() ? Vec2::Zero() : Vec2((box.min + box.max) / 2.0);
}

}  // namespace irgs::editing
