#include "core/editing/map_edit.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

#include "core/world/map_file.hpp"

namespace irgs::editing {
namespace {

Wall wall(std::string id, std::vector<Vec2> points, bool closed = false) {
  Wall w;
  w.id = std::move(id);
  w.points = std::move(points);
  w.closed = closed;
  return w;
}

WorldMap room() {
  WorldMap map;
  map.name = "room";
  map.walls.push_back(wall("room", {{0, 0}, {4, 0}, {4, 3}, {0, 3}}, true));
  Obstacle box;
  box.id = "box";
  box.polygon = {{1, 1}, {1.5, 1}, {1.5, 1.5}, {1, 1.5}};
  map.obstacles.push_back(box);
  PointFeature corner;
  corner.id = "c1";
  corner.position = {0, 0};
  map.features.push_back(corner);
  map.start = Pose2{2.0, 2.0, 0.0};
  return map;
}

TEST(MapEdit, AddThenRevertRestoresTheSavedFileByteForByte) {
  WorldMap map = room();
  const std::string before = serializeMap(map);
  const Edit edit = addElement(map, wall("", {{0.5, 0.5}, {2.5, 0.5}}));
  applyEdit(map, edit);
  ASSERT_EQ(map.walls.size(), 2u);
  EXPECT_EQ(map.walls[1].id, "wall-1");
  EXPECT_EQ(edit.selection_after, (std::vector<ElementRef>{{ElementKind::kWall, 1}}));
  revertEdit(map, edit);
  EXPECT_EQ(serializeMap(map), before);
}

TEST(MapEdit, AddedIdsNeverCollideWithExistingOnes) {
  WorldMap map = room();
  map.walls.push_back(wall("wall-1", {{0, 0}, {1, 0}}));
  Edit edit = addElement(map, wall("room", {{0, 1}, {1, 1}}));  // taken id
  applyEdit(map, edit);
  EXPECT_EQ(map.walls.back().id, "wall-2");
}

TEST(MapEdit, ObstaclesAreStoredCounterClockwise) {
  WorldMap map = room();
  Obstacle cw;
  cw.polygon = {{2, 2}, {2, 2.5}, {2.5, 2.5}, {2.5, 2}};  // clockwise
  applyEdit(map, addElement(map, cw));
  const auto& poly = map.obstacles.back().polygon;
  double area2 = 0.0;
  for (std::size_t i = 0; i < poly.size(); ++i)
    area2 += cross(poly[i], poly[(i + 1) % poly.size()]);
  EXPECT_GT(area2, 0.0);
}

TEST(MapEdit, InvalidElementsAreRejected) {
  const WorldMap map = room();
  EXPECT_THROW(addElement(map, wall("", {{0, 0}})), std::invalid_argument);
  Obstacle two;
  two.polygon = {{0, 0}, {1, 1}};
  EXPECT_THROW(addElement(map, two), std::invalid_argument);
  EXPECT_THROW(addElement(map, wall("", {{0, 0}, {std::nan(""), 1}})), std::invalid_argument);
  EXPECT_THROW(setStart(map, Pose2{0, 0, std::numeric_limits<double>::infinity()}),
               std::invalid_argument);
}

TEST(MapEdit, MoveShiftsEverySelectedElementAndUndoes) {
  WorldMap map = room();
  const std::vector<ElementRef> sel = {
      {ElementKind::kObstacle, 0}, {ElementKind::kFeature, 0}, {ElementKind::kStart, 0}};
  const Edit edit = moveElements(map, sel, Vec2(0.5, -0.25));
  applyEdit(map, edit);
  EXPECT_DOUBLE_EQ(map.obstacles[0].polygon[0].x(), 1.5);
  EXPECT_DOUBLE_EQ(map.obstacles[0].polygon[0].y(), 0.75);
  EXPECT_DOUBLE_EQ(map.features[0].position.x(), 0.5);
  EXPECT_DOUBLE_EQ(map.start.x, 2.5);
  EXPECT_DOUBLE_EQ(map.walls[0].points[0].x(), 0.0);  // not selected
  revertEdit(map, edit);
  EXPECT_EQ(serializeMap(map), serializeMap(room()));
}

TEST(MapEdit, RotateTurnsAboutThePivotAndTurnsTheStartHeading) {
  WorldMap map = room();
  const Edit edit = rotateElements(map, {{ElementKind::kStart, 0}, {ElementKind::kFeature, 0}},
                                   kPi / 2.0, Vec2(1.0, 0.0));
  applyEdit(map, edit);
  EXPECT_NEAR(map.features[0].position.x(), 1.0, 1e-12);  // (0,0) about (1,0) by 90 deg
  EXPECT_NEAR(map.features[0].position.y(), -1.0, 1e-12);
  EXPECT_NEAR(map.start.x, -1.0, 1e-12);  // (2,2) -> (-1, 1)
  EXPECT_NEAR(map.start.y, 1.0, 1e-12);
  EXPECT_NEAR(map.start.theta, kPi / 2.0, 1e-12);
}

TEST(MapEdit, DeletingSeveralElementsOfOneKindUndoesInOrder) {
  WorldMap map = room();
  map.walls.push_back(wall("a", {{0, 0}, {1, 0}}));
  map.walls.push_back(wall("b", {{0, 1}, {1, 1}}));
  map.walls.push_back(wall("c", {{0, 2}, {1, 2}}));
  const std::string before = serializeMap(map);
  const Edit edit = deleteElements(
      map, {{ElementKind::kWall, 1}, {ElementKind::kWall, 3}, {ElementKind::kStart, 0}});
  applyEdit(map, edit);
  ASSERT_EQ(map.walls.size(), 2u);
  EXPECT_EQ(map.walls[0].id, "room");
  EXPECT_EQ(map.walls[1].id, "b");
  EXPECT_DOUBLE_EQ(map.start.x, 2.0);  // the start pose cannot be deleted
  revertEdit(map, edit);
  EXPECT_EQ(serializeMap(map), before);
}

TEST(MapEdit, MoveVertexChangesOnePointOnly) {
  WorldMap map = room();
  applyEdit(map, moveVertex(map, {ElementKind::kWall, 0}, 2, Vec2(5, 3)));
  EXPECT_EQ(map.walls[0].points[2], Vec2(5, 3));
  EXPECT_EQ(map.walls[0].points[1], Vec2(4, 0));
  EXPECT_THROW(moveVertex(map, {ElementKind::kWall, 0}, 9, Vec2(0, 0)), std::out_of_range);
  EXPECT_THROW(moveVertex(map, {ElementKind::kFeature, 0}, 0, Vec2(0, 0)), std::out_of_range);
}

TEST(MapEdit, CopyPasteAddsOffsetCopiesWithFreshIds) {
  WorldMap map = room();
  const Clipboard clip = copyElements(map, {{ElementKind::kObstacle, 0}, {ElementKind::kStart, 0}});
  ASSERT_EQ(clip.size(), 1u);  // the start pose is not copied
  const Edit edit = pasteElements(map, clip, Vec2(1.0, 0.0));
  applyEdit(map, edit);
  ASSERT_EQ(map.obstacles.size(), 2u);
  EXPECT_NE(map.obstacles[1].id, "box");
  EXPECT_DOUBLE_EQ(map.obstacles[1].polygon[0].x(), 2.0);
  EXPECT_EQ(edit.selection_after, (std::vector<ElementRef>{{ElementKind::kObstacle, 1}}));
}

TEST(MapEdit, ReplaceElementKeepsIdsUniqueAndKindsMatching) {
  const WorldMap map = room();
  Wall renamed = map.walls[0];
  renamed.id = "box";  // the obstacle's id
  EXPECT_THROW(replaceElement(map, {ElementKind::kWall, 0}, renamed), std::invalid_argument);
  EXPECT_THROW(replaceElement(map, {ElementKind::kWall, 0}, map.obstacles[0]),
               std::invalid_argument);
  renamed.id = "outline";
  WorldMap edited = map;
  applyEdit(edited, replaceElement(map, {ElementKind::kWall, 0}, renamed));
  EXPECT_EQ(edited.walls[0].id, "outline");
}

TEST(MapEdit, AnEditThatDoesNotFitTheMapThrowsAndLeavesItUnchanged) {
  WorldMap map = room();
  const Edit edit = deleteElements(map, {{ElementKind::kWall, 0}, {ElementKind::kObstacle, 0}});
  WorldMap other;  // no walls, no obstacles
  EXPECT_THROW(applyEdit(other, edit), std::logic_error);
  EXPECT_TRUE(other.walls.empty());
  EXPECT_THROW(elementAt(map, {ElementKind::kFeature, 5}), std::out_of_range);
  EXPECT_THROW(moveElements(map, {{ElementKind::kWall, 7}}, Vec2(1, 0)), std::out_of_range);
}

TEST(MapEdit, ReplaceContentsTurnsOneMapIntoAnotherAndBack) {
  WorldMap map = room();
  WorldMap target;
  target.walls.push_back(wall("x", {{0, 0}, {9, 9}}));
  target.start = Pose2{1, 1, 1};
  const std::string before = serializeMap(map);
  const Edit edit = replaceContents(map, target, "Recover");
  applyEdit(map, edit);
  ASSERT_EQ(map.walls.size(), 1u);
  EXPECT_EQ(map.walls[0].id, "x");
  EXPECT_TRUE(map.obstacles.empty());
  EXPECT_EQ(map.start, target.start);
  revertEdit(map, edit);
  EXPECT_EQ(serializeMap(map), before);
}

// A recovery restores the calibrated floor plan too, not only the elements.
TEST(MapEdit, ReplaceContentsCarriesTheFloorPlan) {
  WorldMap map = room();
  WorldMap target = map;
  FloorPlan plan;
  plan.source = "plans/plan.png";
  plan.metres_per_pixel = 0.03;
  plan.opacity = 0.3;
  target.floor_plan = plan;
  const Edit edit = replaceContents(map, target, "Recover");
  ASSERT_FALSE(edit.empty());
  applyEdit(map, edit);
  ASSERT_TRUE(map.floor_plan);
  EXPECT_EQ(*map.floor_plan, plan);
  revertEdit(map, edit);
  EXPECT_FALSE(map.floor_plan);
  EXPECT_FALSE(replaceContents(target, target, "Recover").floor_plan);  // unchanged: no change
}

}  // namespace
}  // namespace irgs::editing
