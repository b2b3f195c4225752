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
// (corner/edge), the start pose, ceiling markers and lights, and the topological graph's nodes
// and edges; the raster layer as a whole. World metres and radians.
//
// The graph stays consistent through the builders: a node tied to a marker moves and rotates
// with it (so do an edge's nodes when the edge is moved), renaming a marker or node renames the
// references to it, deleting a node deletes its edges and deleting a marker unties its nodes;
// copies of nodes keep the edges among themselves. Ids are unique within their group (walls,
// obstacles and features share one; markers, lights and nodes each have their own, as in the file
// format); edges have no id.

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "core/geometry/types.hpp"
#include "core/world/world_map.hpp"

namespace irgs::editing {

enum class ElementKind { kWall, kObstacle, kFeature, kStart, kMarker, kLight, kNode, kEdge };

// An element of the map: its kind and index in that kind's vector (0 for the start pose).
struct ElementRef {
  ElementKind kind = ElementKind::kWall;
  std::size_t index = 0;

  friend bool operator==(const ElementRef&, const ElementRef&) = default;
  friend bool operator<(const ElementRef& a, const ElementRef& b) {
    return a.kind != b.kind ? a.kind < b.kind : a.index < b.index;
  }
};

using Element = std::variant<Wall, Obstacle, PointFeature, Pose2, CeilingMarker, CeilingLight,
                             TopoNode, TopoEdge>;

ElementKind kindOf(const Element& element);
// Whether `ref` names an element of `map`.
bool isValidRef(const WorldMap& map, const ElementRef& ref);
// A copy of the element; throws std::out_of_range for an invalid ref.
Element elementAt(const WorldMap& map, const ElementRef& ref);
// The element's id ("" for the start pose and edges).
std::string elementId(const Element& element);
// Human-readable name: "wall 'w3'", "start pose", "edge 'n1' - 'n2'".
std::string describe(const Element& element);
// Bounding box of the element's points (empty for an edge: its points are its nodes').
Box2 elementBounds(const Element& element);
// The element's points in the map: wall points, obstacle vertices, a light's two ends, an edge's
// two node positions (those found), the position of any other element.
std::vector<Vec2> elementPoints(const WorldMap& map, const Element& element);

// The element moved by `delta` / rotated by `angle_rad` (CCW) about `pivot` (an edge is
// unchanged: it follows its nodes).
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

// The floor-plan image (its reference and calibration) replaced, added or removed.
struct FloorPlanChange {
  std::optional<FloorPlan> before;
  std::optional<FloorPlan> after;
};

struct Edit {
  std::string label;                          // for the undo menu ("Add wall")
  std::vector<Change> changes;                // applied in order, reverted in reverse order
  std::vector<ElementRef> selection_after;    // what the editor selects once applied
  std::optional<RasterChange> raster;         // applied after `changes`, reverted before them
  std::optional<FloorPlanChange> floor_plan;  // likewise

  bool empty() const { return changes.empty() && !raster && !floor_plan; }
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
// obstacle with fewer than three, a non-finite coordinate, a marker or light of no size, a node
// tied to a missing marker, an edge to a missing node, an edge repeating another).
Edit addElement(const WorldMap& map, Element element);
Edit setStart(const WorldMap& map, const Pose2& start);
// Replaces one element with a new value of the same kind (numeric editing). Same checks as
// addElement; the id may change but must stay unique (references to a renamed marker or node
// follow it).
Edit replaceElement(const WorldMap& map, const ElementRef& ref, Element element,
                    std::string label = "Edit");
// Moves one vertex of a wall or obstacle (`vertex` indexes points/polygon) or one end of a
// light (0 = a, 1 = b).
Edit moveVertex(const WorldMap& map, const ElementRef& ref, std::size_t vertex, const Vec2& to);
Edit moveElements(const WorldMap& map, const std::vector<ElementRef>& refs, const Vec2& delta);
Edit rotateElements(const WorldMap& map, const std::vector<ElementRef>& refs, double angle_rad,
                    const Vec2& pivot);
// Deletes the elements; the start pose cannot be deleted and is skipped. A deleted node's edges
// go with it; nodes tied to a deleted marker are untied.
Edit deleteElements(const WorldMap& map, const std::vector<ElementRef>& refs);

// Copies of the selected elements (the start pose is not copied; an edge only with both of its
// nodes).
using Clipboard = std::vector<Element>;
Clipboard copyElements(const WorldMap& map, const std::vector<ElementRef>& refs);
// Adds the clipboard's elements moved by `offset`, each with a fresh id; copied edges join the
// copied nodes, copied nodes stay tied to copied markers (and are untied from others).
Edit pasteElements(const WorldMap& map, const Clipboard& clipboard, const Vec2& offset);

// Turns `current`'s editable elements into `target`'s (recovery of autosaved edits as one
// undoable step).
Edit replaceContents(const WorldMap& current, const WorldMap& target, std::string label);

// Puts `layer` under the map's vectors (nothing: removes the raster layer), replacing any
// layer it had. Throws std::invalid_argument for a layer whose cell count does not match its
// size or whose resolution is not > 0.
Edit setRasterLayer(const WorldMap& map, std::optional<RasterLayer> layer);

// Puts the floor plan under the map (nothing: removes it), or recalibrates it. Throws
// std::invalid_argument for an empty source, a scale that is not > 0, a non-finite origin or
// rotation, or an opacity outside 0..1.
Edit setFloorPlan(const WorldMap& map, std::optional<FloorPlan> plan,
                  std::string label = "Set floor plan");

// Centre of the bounding box of the referenced elements (the rotation pivot).
Vec2 selectionCentre(const WorldMap& map, const std::vector<ElementRef>& refs);

}  // namespace irgs::editing
