#include "core/editing/validation.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>

#include "core/editing/hit_test.hpp"

namespace irgs::editing {
namespace {

Wall wall(std::string id, std::vector<Vec2> points, bool closed = false) {
  Wall w;
  w.id = std::move(id);
  w.points = std::move(points);
  w.closed = closed;
  return w;
}

WorldMap closedRoom() {
  WorldMap map;
  map.walls.push_back(wall("room", {{0, 0}, {4, 0}, {4, 3}, {0, 3}}, true));
  map.start = Pose2{2, 1.5, 0};
  return map;
}

std::size_t count(const std::vector<MapIssue>& issues, IssueKind kind) {
  return static_cast<std::size_t>(std::count_if(issues.begin(), issues.end(),
                                                [&](const MapIssue& i) { return i.kind == kind; }));
}

TEST(Validation, AClosedRoomWithAFreeStartHasNoIssues) {
  EXPECT_TRUE(validateMap(closedRoom()).empty());
}

TEST(Validation, WallsJoinedEndToEndOrIntoAnotherWallAreClosed) {
  WorldMap map;
  map.walls.push_back(wall("a", {{0, 0}, {4, 0}, {4, 3}}));
  map.walls.push_back(wall("b", {{4, 3}, {0, 3}, {0, 0}}));
  map.walls.push_back(wall("t", {{2, 0}, {2, 1}}));  // a partition from the middle of a
  map.start = Pose2{1, 1.5, 0};
  EXPECT_TRUE(validateMap(map).empty());
}

TEST(Validation, AWallStoppingShortOfAnotherIsAnUnclosedOutline) {
  WorldMap map;
  map.walls.push_back(wall("a", {{0, 0}, {4, 0}, {4, 3}}));
  map.walls.push_back(wall("b", {{4, 3}, {0, 3}, {0, 0.12}}));  // 12 cm gap at the origin
  map.start = Pose2{2, 1.5, 0};
  const auto issues = validateMap(map);
  ASSERT_EQ(count(issues, IssueKind::kUnclosedOutline), 1u);
  // One gap between the two walls, reported once, at the end that stops short.
  MapIssue gap = issues.front();
  std::sort(gap.elements.begin(), gap.elements.end());
  EXPECT_EQ(gap.elements,
            (std::vector<ElementRef>{{ElementKind::kWall, 0}, {ElementKind::kWall, 1}}));
  EXPECT_EQ(gap.position, Vec2(0, 0.12));
  EXPECT_NE(gap.message.find("0.120 m"), std::string::npos) << gap.message;
}

TEST(Validation, AWallEndingAgainstAnObstacleOrShortOfOneIsNotAGap) {
  WorldMap map = closedRoom();
  Obstacle desk;
  desk.id = "desk";
  desk.polygon = {{2.2, 2.5}, {3.5, 2.5}, {3.5, 3.0}, {2.2, 3.0}};
  map.obstacles.push_back(desk);
  map.walls.push_back(wall("against", {{3.0, 0.0}, {3.0, 2.5}}));  // ends on the desk
  map.walls.push_back(wall("short", {{2.0, 3.0}, {2.0, 2.7}}));    // 0.2 m short of the desk
  map.start = Pose2{1.0, 1.0, 0};
  const auto issues = validateMap(map);
  EXPECT_TRUE(issues.empty()) << issues.front().message;
}

TEST(Validation, AnOpenPolylineWhoseEndsTouchNothingIsFlagged) {
  WorldMap map;
  map.walls.push_back(wall("u", {{0, 0}, {4, 0}, {4, 3}, {0, 3}}));  // closed = false
  map.walls.push_back(wall("board", {{10, 0}, {11, 0}}));            // a lone board is fine
  map.start = Pose2{2, 1.5, 0};
  const auto issues = validateMap(map);
  ASSERT_EQ(issues.size(), 1u);
  EXPECT_EQ(issues[0].kind, IssueKind::kUnclosedOutline);
  EXPECT_EQ(issues[0].elements.front(), (ElementRef{ElementKind::kWall, 0}));
}

TEST(Validation, FeaturesCloserThanTheSeparationOverlap) {
  WorldMap map = closedRoom();
  PointFeature f;
  f.id = "f1";
  f.position = {0, 0};
  map.features.push_back(f);
  f.id = "f2";
  f.position = {0.02, 0};
  map.features.push_back(f);
  f.id = "f3";
  f.position = {4, 0};
  map.features.push_back(f);
  const auto issues = validateMap(map);
  ASSERT_EQ(count(issues, IssueKind::kOverlappingFeatures), 1u);
  EXPECT_EQ(issues[0].elements,
            (std::vector<ElementRef>{{ElementKind::kFeature, 0}, {ElementKind::kFeature, 1}}));
}

TEST(Validation, OverlappingObstaclesAreFlaggedTouchingFreeOnesNot) {
  WorldMap map = closedRoom();
  Obstacle a, b, c;
  a.id = "a";
  a.polygon = {{0.5, 0.5}, {1.0, 0.5}, {1.0, 1.0}, {0.5, 1.0}};
  b.id = "b";
  b.polygon = {{0.6, 0.6}, {0.8, 0.6}, {0.8, 0.8}, {0.6, 0.8}};  // inside a
  c.id = "c";
  c.polygon = {{3, 2}, {3.5, 2}, {3.5, 2.5}};
  map.obstacles = {a, b, c};
  const auto issues = validateMap(map);
  ASSERT_EQ(count(issues, IssueKind::kOverlappingObstacles), 1u);
}

TEST(Validation, AStartPoseOnAWallOrInAnObstacleIsAnError) {
  WorldMap map = closedRoom();
  map.start = Pose2{0.05, 1.5, 0};  // 5 cm from the left wall
  auto issues = validateMap(map);
  ASSERT_EQ(count(issues, IssueKind::kStartInWall), 1u);
  EXPECT_EQ(issues[0].severity, Severity::kError);

  map.start = Pose2{2, 1.5, 0};
  Obstacle o;
  o.id = "table";
  o.polygon = {{1.5, 1}, {2.5, 1}, {2.5, 2}, {1.5, 2}};
  map.obstacles.push_back(o);
  issues = validateMap(map);
  ASSERT_EQ(count(issues, IssueKind::kStartInWall), 1u);
  EXPECT_NE(issues[0].message.find("table"), std::string::npos);

  ValidationSettings s;
  s.robot_radius_m = -1.0;
  EXPECT_THROW(validateMap(map, s), std::invalid_argument);
}

TEST(Validation, ZeroLengthWallsAreDegenerate) {
  WorldMap map = closedRoom();
  map.walls.push_back(wall("dot", {{1, 1}, {1, 1}}));
  EXPECT_EQ(count(validateMap(map), IssueKind::kDegenerateElement), 1u);
}

TEST(HitTest, VerticesBeatPiecesAndObstacleInteriorsAreHit) {
  WorldMap map = closedRoom();
  Obstacle o;
  o.id = "o";
  o.polygon = {{1, 1}, {1.5, 1}, {1.5, 1.5}, {1, 1.5}};
  map.obstacles.push_back(o);
  auto hit = hitTest(map, Vec2(4.02, 0.03), 0.1);
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->ref, (ElementRef{ElementKind::kWall, 0}));
  EXPECT_EQ(hit->vertex, std::optional<std::size_t>(1));
  hit = hitTest(map, Vec2(2.0, 0.05), 0.1);
  ASSERT_TRUE(hit);
  EXPECT_FALSE(hit->vertex);
  hit = hitTest(map, Vec2(1.25, 1.25), 0.01);
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->ref, (ElementRef{ElementKind::kObstacle, 0}));
  EXPECT_FALSE(hitTest(map, Vec2(3.0, 2.5), 0.1));
  const auto boxed = elementsInBox(map, Box2{Vec2(0.9, 0.9), Vec2(2.1, 2.1)});
  EXPECT_EQ(boxed,
            (std::vector<ElementRef>{{ElementKind::kObstacle, 0}, {ElementKind::kStart, 0}}));
}

}  // namespace
}  // namespace irgs::editing
