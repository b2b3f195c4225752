// Editing of the ceiling layers (markers, lights) and the topological graph (nodes, edges):
// the edits keep the graph consistent, undo exactly, hit testing finds the new elements and
// validation reports broken references.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "core/camera/ceiling_scene.hpp"
#include "core/editing/hit_test.hpp"
#include "core/editing/map_edit.hpp"
#include "core/editing/snapping.hpp"
#include "core/editing/validation.hpp"
#include "core/navigation/route_plan.hpp"
#include "core/world/map_file.hpp"

namespace irgs::editing {
namespace {

CeilingMarker marker(std::string id, Vec2 p) {
  CeilingMarker m;
  m.id = std::move(id);
  m.position = p;
  return m;
}

TopoNode node(std::string id, Vec2 p, std::string marker_id = "") {
  TopoNode n;
  n.id = std::move(id);
  n.position = p;
  n.marker_id = std::move(marker_id);
  return n;
}

TopoEdge edge(std::string from, std::string to) {
  TopoEdge e;
  e.from = std::move(from);
  e.to = std::move(to);
  return e;
}

// A 6 x 4 m room with two markers, a light between them and a three-node graph.
WorldMap corridor() {
  WorldMap map;
  Wall w;
  w.id = "room";
  w.points = {{0, 0}, {6, 0}, {6, 4}, {0, 4}};
  w.closed = true;
  map.walls.push_back(w);
  map.start = Pose2{0.5, 0.5, 0.0};
  map.markers = {marker("m0", {1, 2}), marker("m1", {5, 2})};
  CeilingLight light;
  light.id = "l0";
  light.tube = {{2, 2}, {4, 2}};
  map.lights.push_back(light);
  map.graph.nodes = {node("0", {1, 2}, "m0"), node("1", {5, 2}, "m1"), node("2", {5, 3.5})};
  map.graph.edges = {edge("0", "1"), edge("1", "2")};
  return map;
}

TEST(CeilingGraphEdit, AddedMarkersLightsAndNodesGetFreshIdsPerGroupAndUndoByteForByte) {
  WorldMap map = corridor();
  const std::string before = serializeMap(map);
  Edit a = addElement(map, marker("", {3, 1}));
  applyEdit(map, a);
  EXPECT_EQ(map.markers.back().id, "marker-1");
  EXPECT_EQ(a.selection_after, (std::vector<ElementRef>{{ElementKind::kMarker, 2}}));
  // A node may share its id with a marker: the groups are separate, as in the file format.
  Edit b = addElement(map, node("m0", {3, 1}, "marker-1"));
  applyEdit(map, b);
  EXPECT_EQ(map.graph.nodes.back().id, "m0");
  Edit c = addElement(map, node("0", {3, 3}));  // taken node id
  applyEdit(map, c);
  EXPECT_EQ(map.graph.nodes.back().id, "node-1");
  revertEdit(map, c);
  revertEdit(map, b);
  revertEdit(map, a);
  EXPECT_EQ(serializeMap(map), before);
}

TEST(CeilingGraphEdit, InvalidCeilingAndGraphElementsAreRefused) {
  const WorldMap map = corridor();
  CeilingMarker tiny = marker("", {1, 1});
  tiny.size_m = 0.0;
  EXPECT_THROW(addElement(map, tiny), std::invalid_argument);
  CeilingLight dot;
  dot.tube = {{1, 1}, {1, 1}};
  EXPECT_THROW(addElement(map, dot), std::invalid_argument);
  EXPECT_THROW(addElement(map, node("n", {1, 1}, "no-such-marker")), std::invalid_argument);
  EXPECT_THROW(addElement(map, edge("0", "9")), std::invalid_argument);  // missing node
  EXPECT_THROW(addElement(map, edge("2", "2")), std::invalid_argument);  // a loop
  EXPECT_THROW(addElement(map, edge("1", "0")), std::invalid_argument);  // repeats 0-1
  TopoEdge free_cost = edge("0", "2");
  free_cost.cost_m = -1.0;
  EXPECT_THROW(addElement(map, free_cost), std::invalid_argument);
  free_cost.cost_m = 6.5;
  WorldMap copy = map;
  applyEdit(copy, addElement(copy, free_cost));
  EXPECT_EQ(copy.graph.edges.size(), 3u);
}

TEST(CeilingGraphEdit, MovingAMarkerTakesItsNodeAlongAndUndoes) {
  WorldMap map = corridor();
  const std::string before = serializeMap(map);
  const Edit move = moveElements(map, {{ElementKind::kMarker, 0}}, {0.5, -0.25});
  applyEdit(map, move);
  EXPECT_TRUE(map.markers[0].position.isApprox(Vec2(1.5, 1.75)));
  EXPECT_TRUE(map.graph.nodes[0].position.isApprox(Vec2(1.5, 1.75)));  // tied to m0
  EXPECT_TRUE(map.graph.nodes[1].position.isApprox(Vec2(5, 2)));       // tied to m1: stays
  EXPECT_EQ(move.selection_after, (std::vector<ElementRef>{{ElementKind::kMarker, 0}}));
  revertEdit(map, move);
  EXPECT_EQ(serializeMap(map), before);
}

TEST(CeilingGraphEdit, MovingAnEdgeMovesItsNodes) {
  WorldMap map = corridor();
  applyEdit(map, moveElements(map, {{ElementKind::kEdge, 1}}, {0.0, 0.25}));
  EXPECT_TRUE(map.graph.nodes[0].position.isApprox(Vec2(1, 2)));
  EXPECT_TRUE(map.graph.nodes[1].position.isApprox(Vec2(5, 2.25)));
  EXPECT_TRUE(map.graph.nodes[2].position.isApprox(Vec2(5, 3.75)));
  EXPECT_TRUE(map.markers[1].position.isApprox(Vec2(5, 2)));  // a node does not move its marker
}

TEST(CeilingGraphEdit, RotatingTurnsMarkerHeadingsAndLightTubes) {
  WorldMap map = corridor();
  const double quarter = std::numbers::pi / 2.0;
  applyEdit(map, rotateElements(map, {{ElementKind::kMarker, 0}, {ElementKind::kLight, 0}}, quarter,
                                {3, 2}));
  EXPECT_NEAR(map.markers[0].heading_rad, quarter, 1e-12);
  EXPECT_TRUE(map.markers[0].position.isApprox(Vec2(3, 0)));
  EXPECT_TRUE(map.lights[0].tube.a.isApprox(Vec2(3, 1)));
  EXPECT_TRUE(map.lights[0].tube.b.isApprox(Vec2(3, 3)));
  EXPECT_TRUE(map.graph.nodes[0].position.isApprox(Vec2(3, 0)));  // follows m0
}

TEST(CeilingGraphEdit, MovingALightEndChangesItsLengthAndOrientation) {
  WorldMap map = corridor();
  applyEdit(map, moveVertex(map, {ElementKind::kLight, 0}, 1, {2, 4}));
  EXPECT_TRUE(map.lights[0].tube.a.isApprox(Vec2(2, 2)));
  EXPECT_TRUE(map.lights[0].tube.b.isApprox(Vec2(2, 4)));
  EXPECT_THROW(moveVertex(map, {ElementKind::kLight, 0}, 2, {0, 0}), std::out_of_range);
}

TEST(CeilingGraphEdit, RenamingANodeOrMarkerRenamesItsReferences) {
  WorldMap map = corridor();
  const std::string before = serializeMap(map);
  TopoNode renamed = map.graph.nodes[1];
  renamed.id = "junction";
  const Edit e1 = replaceElement(map, {ElementKind::kNode, 1}, renamed, "Rename");
  applyEdit(map, e1);
  EXPECT_EQ(map.graph.edges[0].to, "junction");
  EXPECT_EQ(map.graph.edges[1].from, "junction");
  CeilingMarker m = map.markers[0];
  m.id = "red-0";
  const Edit e2 = replaceElement(map, {ElementKind::kMarker, 0}, m, "Rename");
  applyEdit(map, e2);
  EXPECT_EQ(map.graph.nodes[0].marker_id, "red-0");
  // A marker edited to a new position takes its node along.
  m.position = {1.5, 2.5};
  const Edit e3 = replaceElement(map, {ElementKind::kMarker, 0}, m, "Edit position");
  applyEdit(map, e3);
  EXPECT_TRUE(map.graph.nodes[0].position.isApprox(Vec2(1.5, 2.5)));
  revertEdit(map, e3);
  EXPECT_TRUE(validateMap(map).empty());
  // Taken ids within the group are refused.
  TopoNode clash = map.graph.nodes[0];
  clash.id = "2";
  EXPECT_THROW(replaceElement(map, {ElementKind::kNode, 0}, clash), std::invalid_argument);
  revertEdit(map, e2);
  revertEdit(map, e1);
  EXPECT_EQ(serializeMap(map), before);
}

TEST(CeilingGraphEdit, DeletingANodeDeletesItsEdgesAndAMarkerUntiesItsNodes) {
  WorldMap map = corridor();
  const std::string before = serializeMap(map);
  const Edit del = deleteElements(map, {{ElementKind::kNode, 1}, {ElementKind::kMarker, 0}});
  applyEdit(map, del);
  EXPECT_TRUE(map.graph.edges.empty());  // both edges touched node 1
  ASSERT_EQ(map.graph.nodes.size(), 2u);
  EXPECT_EQ(map.graph.nodes[0].id, "0");
  EXPECT_EQ(map.graph.nodes[0].marker_id, "");  // m0 is gone
  ASSERT_EQ(map.markers.size(), 1u);
  EXPECT_EQ(map.markers[0].id, "m1");
  EXPECT_TRUE(validateMap(map).empty());
  revertEdit(map, del);
  EXPECT_EQ(serializeMap(map), before);
}

TEST(CeilingGraphEdit, CopyPasteRemapsEdgesAndMarkerTiesToTheCopies) {
  WorldMap map = corridor();
  // Marker m1, nodes 1 and 2 and both edges: the 0-1 edge lacks node 0, so it is not copied.
  const Clipboard clip = copyElements(map, {{ElementKind::kMarker, 1},
                                            {ElementKind::kNode, 1},
                                            {ElementKind::kNode, 2},
                                            {ElementKind::kEdge, 0},
                                            {ElementKind::kEdge, 1}});
  ASSERT_EQ(clip.size(), 4u);
  const Edit paste = pasteElements(map, clip, {-3.0, 0.0});
  applyEdit(map, paste);
  ASSERT_EQ(map.markers.size(), 3u);
  ASSERT_EQ(map.graph.nodes.size(), 5u);
  ASSERT_EQ(map.graph.edges.size(), 3u);
  const CeilingMarker& m = map.markers[2];
  const TopoNode& n1 = map.graph.nodes[3];
  const TopoNode& n2 = map.graph.nodes[4];
  EXPECT_TRUE(m.position.isApprox(Vec2(2, 2)));
  EXPECT_EQ(n1.marker_id, m.id);
  EXPECT_EQ(n2.marker_id, "");
  EXPECT_EQ(map.graph.edges[2].from, n1.id);
  EXPECT_EQ(map.graph.edges[2].to, n2.id);
  EXPECT_EQ(paste.selection_after.size(), 4u);
  EXPECT_TRUE(validateMap(map).empty());
}

TEST(CeilingGraphEdit, HitTestFindsNodesOverMarkersMarkersLightsAndEdges) {
  const WorldMap map = corridor();
  // On the node at the marker's centre: the node; on the marker's square away from it: the marker.
  auto hit = hitTest(map, {1.01, 2.0}, 0.05);
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->ref, (ElementRef{ElementKind::kNode, 0}));
  hit = hitTest(map, {1.08, 2.08}, 0.05);
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->ref, (ElementRef{ElementKind::kMarker, 0}));
  // The light's end is a vertex; its middle hits the light (before the 0-1 edge under it).
  hit = hitTest(map, {4.01, 2.0}, 0.05);
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->ref, (ElementRef{ElementKind::kLight, 0}));
  EXPECT_EQ(hit->vertex, std::optional<std::size_t>(1));
  hit = hitTest(map, {3.0, 2.02}, 0.05);
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->ref, (ElementRef{ElementKind::kLight, 0}));
  EXPECT_FALSE(hit->vertex);
  hit = hitTest(map, {5.03, 2.75}, 0.05);  // between nodes 1 and 2
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->ref, (ElementRef{ElementKind::kEdge, 1}));
  const auto boxed = elementsInBox(map, Box2{{4.5, 1.5}, {5.5, 3.8}});
  EXPECT_EQ(boxed, (std::vector<ElementRef>{{ElementKind::kMarker, 1},
                                            {ElementKind::kNode, 1},
                                            {ElementKind::kNode, 2},
                                            {ElementKind::kEdge, 1}}));
}

TEST(CeilingGraphEdit, SnapTargetsIncludeMarkerCentresLightEndsAndNodes) {
  const WorldMap map = corridor();
  const auto targets = snapTargets(map, {{ElementKind::kMarker, 1}, {ElementKind::kNode, 1}});
  auto has = [&](Vec2 p) {
    return std::any_of(targets.begin(), targets.end(),
                       [&](const Vec2& q) { return (q - p).norm() < 1e-12; });
  };
  EXPECT_TRUE(has({1, 2}));
  EXPECT_TRUE(has({3, 2}));  // the light's middle
  EXPECT_TRUE(has({5, 3.5}));
  EXPECT_FALSE(has({5, 2}));  // marker m1 and node 1 are excluded
}

std::size_t count(const std::vector<MapIssue>& issues, IssueKind kind) {
  return static_cast<std::size_t>(std::count_if(issues.begin(), issues.end(),
                                                [&](const MapIssue& i) { return i.kind == kind; }));
}

TEST(CeilingGraphValidation, BrokenReferencesDuplicatesAndOutsideElementsAreReported) {
  WorldMap map = corridor();
  EXPECT_TRUE(validateMap(map).empty());
  map.graph.edges.push_back(edge("2", "ghost"));
  map.graph.nodes.push_back(node("2", {3, 3}));  // duplicate id
  map.graph.nodes.push_back(node("9", {3, 1}, "gone"));
  map.markers.push_back(marker("far", {10, 2}));
  const auto issues = validateMap(map);
  EXPECT_EQ(count(issues, IssueKind::kMissingNode), 1u);
  EXPECT_EQ(count(issues, IssueKind::kDuplicateId), 1u);
  EXPECT_EQ(count(issues, IssueKind::kMissingMarker), 1u);
  EXPECT_EQ(count(issues, IssueKind::kOutsideMap), 1u);
  for (const MapIssue& i : issues) {
    if (i.kind == IssueKind::kOutsideMap) {
      EXPECT_EQ(i.elements, (std::vector<ElementRef>{{ElementKind::kMarker, 2}}));
      EXPECT_EQ(i.severity, Severity::kWarning);
    }
    if (i.kind == IssueKind::kMissingNode) {
      EXPECT_EQ(i.severity, Severity::kError);
    }
  }
}

TEST(CeilingGraphValidation, AGivenCostBelowTheChordIsFlagged) {
  WorldMap map = corridor();
  map.graph.edges[0].cost_m = 3.0;  // the nodes are 4 m apart
  EXPECT_EQ(count(validateMap(map), IssueKind::kEdgeCostBelowDistance), 1u);
  map.graph.edges[0].cost_m = 4.5;
  EXPECT_TRUE(validateMap(map).empty());
}

TEST(EdgeCost, GivenCostsOverrideTheChordAndThePlannerUsesThem) {
  WorldMap map = corridor();
  // 0 -> 2 directly (chord 4.27 m) against 0 -> 1 -> 2 (4 + 1.5 m).
  map.graph.edges.push_back(edge("0", "2"));
  EXPECT_NEAR(*map.graph.edgeCost(map.graph.edges[2]), std::hypot(4.0, 1.5), 1e-12);
  RoutePlan plan = planRoute(map.graph, "0", "2");
  ASSERT_EQ(plan.status, RouteStatus::kOk);
  EXPECT_EQ(plan.steps.size(), 2u);
  // The direct corridor bends: 7 m long. The route goes through node 1 now.
  map.graph.edges[2].cost_m = 7.0;
  EXPECT_NEAR(*map.graph.edgeCost(map.graph.edges[2]), 7.0, 1e-12);
  plan = planRoute(map.graph, "0", "2");
  ASSERT_EQ(plan.status, RouteStatus::kOk);
  EXPECT_EQ(plan.steps.size(), 3u);
  EXPECT_NEAR(plan.length_m, 5.5, 1e-12);
  // A cost below the chord keeps the search optimal (no heuristic then).
  map.graph.edges[0].cost_m = 0.5;
  plan = planRoute(map.graph, "0", "2");
  EXPECT_NEAR(plan.length_m, 2.0, 1e-12);
  EXPECT_FALSE(map.graph.edgeCost(edge("0", "nope")));
}

TEST(CeilingGraphFormat, ColourAndCostRoundTripAndDefaultsAreNotWritten) {
  WorldMap map = corridor();
  const std::string plain = serializeMap(map);
  EXPECT_EQ(plain.find("colour"), std::string::npos);
  EXPECT_EQ(plain.find("cost_m"), std::string::npos);
  map.markers[1].colour = {0, 128, 255};
  map.graph.edges[1].cost_m = 2.25;
  const std::string text = serializeMap(map);
  EXPECT_NE(text.find("\"colour\": \"#0080ff\""), std::string::npos);
  const MapLoadResult loaded = parseMapJson(text, "test.json", ".");
  ASSERT_TRUE(loaded.map);
  EXPECT_EQ(loaded.map->markers[1].colour, (ColourRgb{0, 128, 255}));
  EXPECT_EQ(loaded.map->graph.edges[1].cost_m, std::optional<double>(2.25));
  EXPECT_EQ(serializeMap(*loaded.map), text);
  // Bad values are located errors.
  std::string bad = text;
  bad.replace(bad.find("#0080ff"), 7, "blue!!!");
  const MapLoadResult refused = parseMapJson(bad, "bad.json", ".");
  EXPECT_FALSE(refused.map);
  ASSERT_FALSE(refused.diagnostics.empty());
  EXPECT_NE(refused.diagnostics.front().toString().find("/ceiling_markers/1/colour"),
            std::string::npos);
}

TEST(CeilingGraphFormat, TheCameraPaintsAMarkerOfAnotherColourAsADecoration) {
  WorldMap map = corridor();
  map.markers[1].colour = {0, 128, 255};
  const CeilingScene scene = sceneFromMap(map);
  ASSERT_EQ(scene.markers.size(), 1u);  // only the red one is a marker to detect
  EXPECT_TRUE(scene.markers[0].centre.isApprox(Vec2(1, 2)));
  ASSERT_EQ(scene.decorations.size(), 1u);
  EXPECT_TRUE(scene.decorations[0].rect.centre.isApprox(Vec2(5, 2)));
  EXPECT_NEAR(scene.decorations[0].albedo.b, 1.0, 1e-12);
  EXPECT_NEAR(scene.decorations[0].albedo.g, 128.0 / 255.0, 1e-12);
}

}  // namespace
}  // namespace irgs::editing
