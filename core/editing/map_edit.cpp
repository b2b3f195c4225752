#include "core/editing/map_edit.hpp"

#include <algorithm>
#include <cmath>
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
  }
  return "element";
}

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
             },
             element);
}

void setId(Element& element, std::string id) {
  std::visit(
      Overloaded{[&](Wall& w) { w.id = std::move(id); }, [&](Obstacle& o) { o.id = std::move(id); },
                 [&](PointFeature& f) { f.id = std::move(id); }, [](Pose2&) {}},
      element);
}

// Obstacles are stored counter-clockwise (as the loader does); the start heading is wrapped.
Element normalised(Element element) {
  if (auto* o = std::get_if<Obstacle>(&element)) {
    if (signedArea2(o->polygon) < 0.0)
      std::reverse(o->polygon.begin(), o->polygon.end());
  } else if (auto* p = std::get_if<Pose2>(&element)) {
    p->theta = wrapAngle(p->theta);
  }
  return element;
}

std::unordered_set<std::string> usedIds(const WorldMap& map) {
  std::unordered_set<std::string> ids;
  for (const Wall& w : map.walls)
    ids.insert(w.id);
  for (const Obstacle& o : map.obstacles)
    ids.insert(o.id);
  for (const PointFeature& f : map.features)
    ids.insert(f.id);
  return ids;
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

template <class F>
Edit transformEach(const WorldMap& map, const std::vector<ElementRef>& refs, std::string label,
                   F transform) {
  Edit edit;
  edit.label = std::move(label);
  for (const ElementRef& r : cleanRefs(map, refs)) {
    Element before = elementAt(map, r);
    Element after = normalised(transform(before));
    checkElement(after);
    edit.changes.push_back({r.kind, r.index, std::move(before), std::move(after)});
    edit.selection_after.push_back(r);
  }
  return edit;
}

}  // namespace

ElementKind kindOf(const Element& element) {
  return std::visit(Overloaded{[](const Wall&) { return ElementKind::kWall; },
                               [](const Obstacle&) { return ElementKind::kObstacle; },
                               [](const PointFeature&) { return ElementKind::kFeature; },
                               [](const Pose2&) { return ElementKind::kStart; }},
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
  }
  return map.start;
}

std::string elementId(const Element& element) {
  return std::visit(
      Overloaded{[](const Wall& w) { return w.id; }, [](const Obstacle& o) { return o.id; },
                 [](const PointFeature& f) { return f.id; },
                 [](const Pose2&) { return std::string(); }},
      element);
}

std::string describe(const Element& element) {
  const ElementKind kind = kindOf(element);
  if (kind == ElementKind::kStart)
    return kindName(kind);
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
                        [&](const Pose2& p) { box.extend(p.position()); }},
             element);
  return box;
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
                        }},
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
                 }},
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
  std::unordered_set<std::string> used = usedIds(map);
  const std::string id = elementId(element);
  if (id.empty() || used.count(id) > 0)
    setId(element, freshId(used, idPrefix(kind)));
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
  if (ref.kind != ElementKind::kStart && id != elementId(before)) {
    if (id.empty() || usedIds(map).count(id) > 0)
      throw std::invalid_argument("id '" + id + "' is empty or already used");
  }
  Edit edit;
  edit.label = std::move(label);
  edit.changes.push_back({ref.kind, ref.index, std::move(before), normalised(std::move(element))});
  edit.selection_after.push_back(ref);
  return edit;
}

Edit moveVertex(const WorldMap& map, const ElementRef& ref, std::size_t vertex, const Vec2& to) {
  Element element = elementAt(map, ref);
  std::vector<Vec2>* points = nullptr;
  if (auto* w = std::get_if<Wall>(&element))
    points = &w->points;
  else if (auto* o = std::get_if<Obstacle>(&element))
    points = &o->polygon;
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
  std::vector<ElementRef> sorted = cleanRefs(map, refs);
  Edit edit;
  edit.label = "Delete";
  // Highest index first within each kind, so earlier erasures do not shift later ones.
  for (auto it = sorted.rbegin(); it != sorted.rend(); ++it) {
    if (it->kind == ElementKind::kStart)
      continue;
    edit.changes.push_back({it->kind, it->index, elementAt(map, *it), std::nullopt});
  }
  return edit;
}

Clipboard copyElements(const WorldMap& map, const std::vector<ElementRef>& refs) {
  Clipboard out;
  for (const ElementRef& r : cleanRefs(map, refs)) {
    if (r.kind != ElementKind::kStart)
      out.push_back(elementAt(map, r));
  }
  return out;
}

Edit pasteElements(const WorldMap& map, const Clipboard& clipboard, const Vec2& offset) {
  if (!finite(offset))
    throw std::invalid_argument("pasteElements: offset is not finite");
  std::unordered_set<std::string> used = usedIds(map);
  Edit edit;
  edit.label = "Paste";
  std::size_t next[3] = {map.walls.size(), map.obstacles.size(), map.features.size()};
  for (const Element& source : clipboard) {
    const ElementKind kind = kindOf(source);
    if (kind == ElementKind::kStart)
      continue;
    Element e = normalised(translated(source, offset));
    checkElement(e);
    setId(e, freshId(used, idPrefix(kind)));
    const std::size_t index = next[static_cast<int>(kind)]++;
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
  if (!(current.start == target.start))
    edit.changes.push_back({ElementKind::kStart, 0, Element(current.start), Element(target.start)});
  return edit;
}

Vec2 selectionCentre(const WorldMap& map, const std::vector<ElementRef>& refs) {
  Box2 box;
  for (const ElementRef& r : refs) {
    if (isValidRef(map, r))
      box.extend(elementBounds(elementAt(map, r)));
  }
  return box.empty() ? Vec2::Zero() : Vec2((box.min + box.max) / 2.0);
}

}  // namespace irgs::editing
