#pragma once
// Edits of a WorldMap as reversible values: the editor's commands.
//
// An Edit is a list of element changes (insert, replace, erase), each holding the element before
// and after, so applying and reverting are exact and need no snapshot of the whole map (a raster
// layer is copied only by setRasterLayer, the import that replaces it). Builders such as
// addElement() or moveElements() are pure: they read the map and return the Edit; applyEdit()
// performs it. Edits must be applied and reverted in stack order (what QUndoStack guarantees): a
// change addresses its element by index. Misuse (an index outside the map, an element of the wrong
// kind) throws; ordinary editing never does.
//
// Editable elements: walls (polylines, open or closed), polygon obstacles, point features
// (corner/edge) and the start pose; the raster layer as a whole. World metres and radians.

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "core/geometry/types.hpp"
#include "core/world/world_map.hpp"

namespace irgs::editing {

enum class ElementKind { kWall, kObstacle, kFeature, kStart };

// An element of the map: its kind and index in that kind's vector (0 for the start pose).
struct ElementRef {
  ElementKind kind = ElementKind::kWall;
  std::size_t index = 0;

  friend bool operator==(const ElementRef&, const ElementRef&) = default;
  friend bool operator<(const ElementRef& a, const ElementRef& b) {
    return a.kind != b.kind ? a.kind < b.kind : a.index < b.index;
  }
};

using Element = std::variant<Wall, Obstacle, PointFeature, Pose2>;

ElementKind kindOf(const Element& element);
// Whether `ref` names an element of `map`.
bool isValidRef(const WorldMap& map, const ElementRef& ref);
// A copy of the element; throws std::out_of_range for an invalid ref.
Element elementAt(const WorldMap& map, const ElementRef& ref);
// The element's id ("" for the start pose).
std::string elementId(const Element& element);
// Human-readable name: "wall 'w3'", "start pose".
std::string describe(const Element& element);
// Bounding box of the element's points.
Box2 elementBounds(const Element& element);

// The element moved by `delta` / rotated by `angle_rad` (CCW) about `pivot`.
Element translated(const Element& element, const Vec2& delta);
Element rotated(const Element& element, double angle_rad, const Vec2& pivot);

struct Change {
  ElementKind kind = ElementKind::kWall;
  std::size_t index = 0;
  std::optional<Element> before;  // empty: an insertion at `index`
  std::optional<Element> after;   // empty: an erasure at `index`
};

// The raster layer replaced (a ROS map imported under the vectors, or removed). The only change
// that holds raster layers: element edits never copy one.
struct RasterChange {
  std::optional<RasterLayer> before;
  std::optional<RasterLayer> after;
};

struct Edit {
  std::string label;                        // for the undo menu ("Add wall")
  std::vector<Change> changes;              // applied in order, reverted in reverse order
  std::vector<ElementRef> selection_after;  // what the editor selects once applied
  std::optional<RasterChange> raster;       // applied after `changes`, reverted before them

  bool empty() const { return changes.empty() && !raster; }
};

// Performs / undoes the edit. Throws std::logic_error when the map does not fit the edit
// (an index out of range, a kind mismatch); the map is then unchanged.
void applyEdit(WorldMap& map, const Edit& edit);
void revertEdit(WorldMap& map, const Edit& edit);

// An id not used by any wall, obstacle or feature: prefix + number ("wall-3").
std::string uniqueId(const WorldMap& map, std::string_view prefix);

// --- Builders (pure) ---------------------------------------------------------------------------

// Adds an element at the end of its kind (a Pose2 sets the start pose). An empty or taken id is
// replaced by a fresh one; obstacle polygons are stored counter-clockwise. Throws
// std::invalid_argument for an element that cannot exist (a wall with fewer than two points, an
// obstacle with fewer than three, a non-finite coordinate).
Edit addElement(const WorldMap& map, Element element);
Edit setStart(const WorldMap& map, const Pose2& start);
// Replaces one element with a new value of the same kind (numeric editing). Same checks as
// addElement; the id may change but must stay unique.
Edit replaceElement(const WorldMap& map, const ElementRef& ref, Element element,
                    std::string label = "Edit");
// Moves one vertex of a wall or obstacle (`vertex` indexes points/polygon).
Edit moveVertex(const WorldMap& map, const ElementRef& ref, std::size_t vertex, const Vec2& to);
Edit moveElements(const WorldMap& map, const std::vector<ElementRef>& refs, const Vec2& delta);
Edit rotateElements(const WorldMap& map, const std::vector<ElementRef>& refs, double angle_rad,
                    const Vec2& pivot);
// Deletes walls, obstacles and features; the start pose cannot be deleted and is skipped.
Edit deleteElements(const WorldMap& map, const std::vector<ElementRef>& refs);

// Copies of the selected walls, obstacles and features (the start pose is not copied).
using Clipboard = std::vector<Element>;
Clipboard copyElements(const WorldMap& map, const std::vector<ElementRef>& refs);
// Adds the clipboard's elements moved by `offset`, each with a fresh id.
Edit pasteElements(const WorldMap& map, const Clipboard& clipboard, const Vec2& offset);

// Turns `current`'s walls, obstacles, features and start pose into `target`'s (recovery of
// autosaved edits as one undoable step).
Edit replaceContents(const WorldMap& current, const WorldMap& target, std::string label);

// Puts `layer` under the map's vectors (nothing: removes the raster layer), replacing any
// layer it had. Throws std::invalid_argument for a layer whose cell count does not match its
// size or whose resolution is not > 0.
Edit setRasterLayer(const WorldMap& map, std::optional<RasterLayer> layer);

// Centre of the bounding box of the referenced elements (the rotation pivot).
Vec2 selectionCentre(const WorldMap& map, const std::vector<ElementRef>& refs);

}  // namespace irgs::editing
