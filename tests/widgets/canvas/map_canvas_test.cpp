#include "widgets/canvas/map_canvas.hpp"

#include <gtest/gtest.h>

#include <QDir>
#include <QImage>
#include <QSignalSpy>
#include <QWheelEvent>
#include <QtTest/QTest>
#include <cmath>

namespace irgs::widgets {
namespace {

// A 4 m x 3 m room with one box obstacle and a few of every annotation.
WorldMap smallRoom() {
  WorldMap map;
  map.name = "room";
  map.walls.push_back({"outer", {{0, 0}, {4, 0}, {4, 3}, {0, 3}}, true, {}});
  map.walls.push_back({"partition", {{2, 3}, {2, 2.2}}, false, {}});
  map.obstacles.push_back({"box", {{3.0, 0.5}, {3.5, 0.5}, {3.5, 1.0}, {3.0, 1.0}}, {}});
  map.features.push_back({"c1", PointFeatureKind::kCorner, {0, 0}, {}});
  map.features.push_back({"e1", PointFeatureKind::kEdge, {2, 2.2}, {}});
  map.markers.push_back({"m1", {1.0, 2.0}, 0.3, 0.2, {}});
  map.lights.push_back({"l1", {{2.5, 2.5}, {3.5, 2.5}}, 0.1, {}});
  map.graph.nodes.push_back({"n1", {1.0, 2.0}, "m1", {}});
  map.graph.nodes.push_back({"n2", {3.0, 2.0}, "", {}});
  map.graph.edges.push_back({"n1", "n2", true, {}});
  return map;
}

RobotProfile squareRobot() {
  RobotProfile profile;
  profile.name = "square";
  profile.body_outline = {{0.15, -0.15}, {0.15, 0.15}, {-0.15, 0.15}, {-0.15, -0.15}};
  SonarSpec front;
  front.name = "front";
  front.mount = {0.15, 0.0, 0.0};
  front.beam_width_rad = degToRad(25.0);
  front.max_range_m = 4.0;
  profile.sonars.push_back(front);
  SonarSpec left = front;
  left.name = "left";
  left.mount = {0.0, 0.15, kPi / 2};
  profile.sonars.push_back(left);
  profile.bumpers.push_back({"front", {0.15, 0.0}, 0.0, 0.1});
  return profile;
}

int grey(QRgb c) {
  return qGray(c);
}

void saveScreenshot(const QImage& image, const char* name) {
  // Set IRGS_SCREENSHOT_DIR to look at what the tests render.
  const QString dir = qEnvironmentVariable("IRGS_SCREENSHOT_DIR");
  if (!dir.isEmpty())
    image.save(QDir(dir).filePath(QString::fromLatin1(name)));
}

class MapCanvasTest : public ::testing::Test {
 protected:
  void SetUp() override {
    canvas.resize(400, 300);
    canvas.setWorldMap(smallRoom());
    canvas.setRobotProfile(squareRobot());
    canvas.zoomToFit();
  }
  QImage render() { return canvas.grab().toImage().convertToFormat(QImage::Format_RGB32); }
  QRgb pixelAt(const QImage& image, const Vec2& world) {
    const QPoint p = canvas.worldToWidget(world).toPoint();
    return image.pixel(p);
  }

  MapCanvas canvas;
};

TEST_F(MapCanvasTest, ZoomToFitShowsTheWholeMapWithAMargin) {
  const QPointF lo = canvas.worldToWidget({0, 0});
  const QPointF hi = canvas.worldToWidget({4, 3});
  EXPECT_GT(lo.x(), 0.0);
  EXPECT_LT(lo.y(), 300.0);
  EXPECT_LT(hi.x(), 400.0);
  EXPECT_GT(hi.y(), 0.0);
  // The limiting direction (here the height: 3 m in 300 px) fills the view up to the padding.
  EXPECT_NEAR(lo.y() - hi.y(), 300.0 - 48.0, 1e-6);
  EXPECT_LT(hi.x() - lo.x(), 400.0 - 48.0);
}

TEST_F(MapCanvasTest, WallPixelsAreDarkAndFloorPixelsLight) {
  const QImage image = render();
  saveScreenshot(image, "irgs_canvas_room.png");
  for (const Vec2& wall : {Vec2(0.0, 1.5), Vec2(4.0, 1.5), Vec2(2.0, 0.0), Vec2(2.0, 2.6)}) {
    EXPECT_LT(grey(pixelAt(image, wall)), 90) << "wall at " << wall.transpose();
  }
  for (const Vec2& floor : {Vec2(1.3, 1.2), Vec2(2.6, 1.65), Vec2(0.7, 0.4)}) {
    EXPECT_GT(grey(pixelAt(image, floor)), 235) << "floor at " << floor.transpose();
  }
  // The obstacle is filled grey: darker than the floor, lighter than a wall.
  const int obstacle = grey(pixelAt(image, {3.25, 0.75}));
  EXPECT_GT(obstacle, 150);
  EXPECT_LT(obstacle, 225);
}

TEST_F(MapCanvasTest, HiddenWallLayerLeavesTheFloor) {
  canvas.setLayerVisible(MapCanvas::Layer::kWalls, false);
  const QImage image = render();
  EXPECT_GT(grey(pixelAt(image, {0.0, 1.5})), 200);
  EXPECT_GT(grey(pixelAt(image, {3.25, 0.75})), 225);
}

TEST_F(MapCanvasTest, RobotIsDrawnAtItsOdometryPose) {
  const QImage before = render();
  TelemetrySample s;
  s.time_s = 1.0;
  s.odometry_pose = {1.0, 1.0, 0.0};
  canvas.setRobotState(s);
  const QImage image = render();
  // Inside the body, beside the heading arrow: robot blue.
  const QRgb body = pixelAt(image, {1.0, 1.12});
  EXPECT_GT(qBlue(body), qRed(body) + 60);
  EXPECT_LT(grey(body), 200);
  // Far from the robot nothing changed.
  EXPECT_EQ(pixelAt(image, {2.8, 1.6}), pixelAt(before, {2.8, 1.6}));
  EXPECT_EQ(canvas.trailSize(), 1u);
}

TEST_F(MapCanvasTest, SonarConeIsDrawnOutToTheEchoRange) {
  TelemetrySample s;
  s.time_s = 1.0;
  s.odometry_pose = {0.5, 1.5, 0.0};
  s.sonar.push_back({0, 2.0, true});  // front: echo at 2 m
  s.sonar.push_back({7, 1.0, true});  // no such sensor: ignored
  s.sonar.push_back({1, NAN, true});  // broken reading: ignored
  canvas.setRobotState(s);
  const QImage image = render();
  // Inside the cone (apex at x = 0.65): tinted orange, i.e. red well above blue.
  const QRgb inside = pixelAt(image, {1.6, 1.5});
  EXPECT_GT(qRed(inside) - qBlue(inside), 25);
  // Beyond the echo range, and beside the cone: untinted floor.
  const QRgb beyond = pixelAt(image, {3.2, 1.5});
  EXPECT_LT(std::abs(qRed(beyond) - qBlue(beyond)), 8);
  const QRgb beside = pixelAt(image, {1.6, 0.6});
  EXPECT_LT(std::abs(qRed(beside) - qBlue(beside)), 8);
}

TEST_F(MapCanvasTest, StaleSonarReadingsAreNotDrawn) {
  TelemetrySample s;
  s.time_s = 1.0;
  s.odometry_pose = {0.5, 1.5, 0.0};
  s.sonar.push_back({0, 2.0, true});
  canvas.setRobotState(s);
  s.time_s = 1.0 + MapCanvas::kSonarStale_s + 0.5;
  s.sonar.clear();
  canvas.setRobotState(s);
  const QRgb inside = pixelAt(render(), {1.6, 1.5});
  EXPECT_LT(std::abs(qRed(inside) - qBlue(inside)), 8);
}

TEST_F(MapCanvasTest, NonFinitePosesAreIgnored) {
  TelemetrySample s;
  s.odometry_pose = {NAN, 1.0, 0.0};
  canvas.setRobotState(s);
  EXPECT_EQ(canvas.trailSize(), 0u);
  s.odometry_pose = {1.0, 1.0, INFINITY};
  canvas.setRobotState(s);
  EXPECT_EQ(canvas.trailSize(), 0u);
  EXPECT_FALSE(render().isNull());
}

TEST_F(MapCanvasTest, TrailIsDecimatedByDistanceAndBounded) {
  TelemetrySample s;
  for (int i = 0; i < 100; ++i) {  // 1 mm steps: one trail point per 2 cm
    s.time_s = i * 0.01;
    s.odometry_pose = {1.0 + i * 0.001, 1.0, 0.0};
    canvas.setRobotState(s);
  }
  EXPECT_EQ(canvas.trailSize(), 5u);
  for (std::size_t i = 0; i < MapCanvas::kMaxTrailPoints + 10; ++i) {
    s.odometry_pose = {static_cast<double>(i % 2), 0.1 * static_cast<double>(i % 3), 0.0};
    canvas.setRobotState(s);
  }
  EXPECT_EQ(canvas.trailSize(), MapCanvas::kMaxTrailPoints);
  canvas.clearTrail();
  EXPECT_EQ(canvas.trailSize(), 0u);
}

TEST_F(MapCanvasTest, WorldAndWidgetCoordinatesRoundTrip) {
  for (const Vec2& p : {Vec2(0, 0), Vec2(4, 3), Vec2(-12.5, 7.25), Vec2(1e3, -1e3)}) {
    const Vec2 back = canvas.widgetToWorld(canvas.worldToWidget(p));
    EXPECT_NEAR(back.x(), p.x(), 1e-9);
    EXPECT_NEAR(back.y(), p.y(), 1e-9);
  }
  // +x is to the right, +y is up.
  EXPECT_GT(canvas.worldToWidget({1, 0}).x(), canvas.worldToWidget({0, 0}).x());
  EXPECT_LT(canvas.worldToWidget({0, 1}).y(), canvas.worldToWidget({0, 0}).y());
}

TEST_F(MapCanvasTest, WheelZoomKeepsTheWorldPointUnderTheCursor) {
  const QPointF cursor(100.0, 80.0);
  const Vec2 before = canvas.widgetToWorld(cursor);
  const double scale = canvas.pixelsPerMetre();
  QSignalSpy view_spy(&canvas, &MapCanvas::viewChanged);
  QWheelEvent wheel(cursor, canvas.mapToGlobal(cursor), QPoint(), QPoint(0, 240), Qt::NoButton,
                    Qt::NoModifier, Qt::NoScrollPhase, false);
  QApplication::sendEvent(&canvas, &wheel);
  EXPECT_NEAR(canvas.pixelsPerMetre(), scale * 1.44, 1e-9);
  const Vec2 after = canvas.widgetToWorld(cursor);
  EXPECT_NEAR(after.x(), before.x(), 1e-9);
  EXPECT_NEAR(after.y(), before.y(), 1e-9);
  EXPECT_GE(view_spy.count(), 1);
}

TEST_F(MapCanvasTest, ZoomIsLimited) {
  canvas.zoomAt({10, 10}, 1e9);
  EXPECT_DOUBLE_EQ(canvas.pixelsPerMetre(), MapCanvas::kMaxPixelsPerMetre);
  canvas.zoomAt({10, 10}, 1e-12);
  EXPECT_DOUBLE_EQ(canvas.pixelsPerMetre(), MapCanvas::kMinPixelsPerMetre);
  EXPECT_FALSE(render().isNull());  // painting at the limits works (no huge allocations)
  canvas.zoomAt({10, 10}, NAN);
  EXPECT_DOUBLE_EQ(canvas.pixelsPerMetre(), MapCanvas::kMinPixelsPerMetre);
}

TEST_F(MapCanvasTest, DraggingPansAndReportsTheCursor) {
  QSignalSpy cursor_spy(&canvas, &MapCanvas::cursorMoved);
  const Vec2 start = canvas.widgetToWorld({200, 150});
  QTest::mousePress(&canvas, Qt::LeftButton, Qt::NoModifier, QPoint(200, 150));
  QMouseEvent move(QEvent::MouseMove, QPointF(250, 120), canvas.mapToGlobal(QPointF(250, 120)),
                   Qt::NoButton, Qt::LeftButton, Qt::NoModifier);
  QApplication::sendEvent(&canvas, &move);
  QTest::mouseRelease(&canvas, Qt::LeftButton, Qt::NoModifier, QPoint(250, 120));
  // The world point grabbed at (200, 150) is now under (250, 120).
  const Vec2 moved = canvas.widgetToWorld({250, 120});
  EXPECT_NEAR(moved.x(), start.x(), 1e-9);
  EXPECT_NEAR(moved.y(), start.y(), 1e-9);
  ASSERT_GE(cursor_spy.count(), 1);
  const QList<QVariant> last = cursor_spy.takeLast();
  EXPECT_NEAR(last.at(0).toDouble(), start.x(), 1e-9);
  EXPECT_NEAR(last.at(1).toDouble(), start.y(), 1e-9);
}

TEST_F(MapCanvasTest, FollowRobotCentresTheRobotAndADragEndsIt) {
  QSignalSpy follow_spy(&canvas, &MapCanvas::followRobotChanged);
  canvas.setFollowRobot(true);
  TelemetrySample s;
  s.odometry_pose = {3.0, 2.0, 0.5};
  canvas.setRobotState(s);
  EXPECT_NEAR(canvas.worldToWidget({3.0, 2.0}).x(), 200.0, 1e-9);
  EXPECT_NEAR(canvas.worldToWidget({3.0, 2.0}).y(), 150.0, 1e-9);
  QTest::mousePress(&canvas, Qt::LeftButton, Qt::NoModifier, QPoint(200, 150));
  QMouseEvent move(QEvent::MouseMove, QPointF(210, 150), canvas.mapToGlobal(QPointF(210, 150)),
                   Qt::NoButton, Qt::LeftButton, Qt::NoModifier);
  QApplication::sendEvent(&canvas, &move);
  QTest::mouseRelease(&canvas, Qt::LeftButton, Qt::NoModifier, QPoint(210, 150));
  EXPECT_FALSE(canvas.followRobot());
  ASSERT_EQ(follow_spy.count(), 2);
  EXPECT_FALSE(follow_spy.at(1).at(0).toBool());
}

TEST_F(MapCanvasTest, EmptyCanvasPaints) {
  MapCanvas empty;
  empty.resize(200, 100);
  empty.zoomToFit();
  const QImage image = empty.grab().toImage();
  ASSERT_FALSE(image.isNull());
  EXPECT_GT(grey(image.pixel(150, 20)), 230);
  EXPECT_DOUBLE_EQ(empty.pixelsPerMetre(), 50.0);
}

TEST_F(MapCanvasTest, OccupancyGridIsDrawnAndUpdatedFromTheDirtyRect) {
  OccupancyGrid grid(0.02);
  canvas.setGrid(&grid);  // nothing observed yet
  const SonarInverseModel model;
  // A wall-like arc 1.2 m in front of (0.5, 1.5), looking along +x.
  for (int i = 0; i < 5; ++i)
    grid.integrateSonar({0.5, 1.5}, 0.0, degToRad(25.0), 1.2, true, model);
  canvas.gridUpdated();
  EXPECT_TRUE(grid.takeDirtyRect().empty());  // the canvas took it
  const QImage image = render();
  // Free space in the cone is tinted blue-white, the arc dark, outside unchanged floor.
  const QRgb free_px = pixelAt(image, {1.0, 1.5});
  EXPECT_GT(qBlue(free_px), qRed(free_px) + 10);
  EXPECT_LT(grey(pixelAt(image, {1.7, 1.5})), 100);
  EXPECT_GT(grey(pixelAt(image, {1.2, 0.6})), 235);

  // Hidden or removed, the grid leaves the floor (sampled off the metric grid lines).
  canvas.setLayerVisible(MapCanvas::Layer::kGrid, false);
  EXPECT_GT(grey(pixelAt(render(), {1.7, 1.45})), 235);
  canvas.setLayerVisible(MapCanvas::Layer::kGrid, true);
  canvas.setGrid(nullptr);
  EXPECT_GT(grey(pixelAt(render(), {1.7, 1.45})), 235);
}

TEST_F(MapCanvasTest, ConstGridIsRedrawnWhole) {
  OccupancyGrid grid(0.02);
  const SonarInverseModel model;
  const OccupancyGrid& view = grid;
  canvas.setGrid(&view);
  for (int i = 0; i < 5; ++i)
    grid.integrateSonar({0.5, 1.5}, 0.0, degToRad(25.0), 1.2, true, model);
  canvas.gridUpdated();
  EXPECT_FALSE(grid.takeDirtyRect().empty());  // a const grid's rect is left alone
  EXPECT_LT(grey(pixelAt(render(), {1.7, 1.5})), 100);
}

TEST_F(MapCanvasTest, GridGrowthAcrossTilesKeepsEarlierCells) {
  OccupancyGrid grid(0.01);
  canvas.setGrid(&grid);
  const SonarInverseModel model;
  for (int i = 0; i < 4; ++i)
    grid.integrateSonar({0.5, 1.5}, 0.0, degToRad(25.0), 1.2, true, model);
  canvas.gridUpdated();
  // Far away, in other tiles (256 cells = 2.56 m at 1 cm) and at negative cell indices.
  for (int i = 0; i < 4; ++i)
    grid.integrateSonar({-3.0, -2.0}, kPi, degToRad(25.0), 1.0, true, model);
  canvas.gridUpdated();
  canvas.setView({1.7, 1.5}, 400.0);  // close enough that the 3 cm arc is solid
  EXPECT_LT(grey(pixelAt(render(), {1.7, 1.5})), 90);
  canvas.setView({-4.0, -2.0}, 400.0);
  EXPECT_LT(grey(pixelAt(render(), {-4.0, -2.0})), 90);
  canvas.zoomToFit();  // both in view, cells far below a pixel: drawn from the reduced tiles
  const QImage overview = render();
  saveScreenshot(overview, "irgs_canvas_grid_overview.png");
  EXPECT_LT(grey(pixelAt(overview, {1.7, 1.5})), 200);
  EXPECT_LT(grey(pixelAt(overview, {-4.0, -2.0})), 200);
}

TEST_F(MapCanvasTest, TruthGhostAndBumpersAreDrawn) {
  TelemetrySample s;
  s.time_s = 2.0;
  s.odometry_pose = {1.0, 1.5, 0.0};
  s.true_pose = Pose2{1.2, 1.8, 0.3};
  s.bumpers = 1u;  // front bumper pressed
  canvas.zoomAt(canvas.worldToWidget({1.0, 1.5}), 3.0);
  canvas.setRobotState(s);
  const QImage image = render();
  saveScreenshot(image, "irgs_canvas_robot.png");
  // The pressed bumper is red at the middle of the front face.
  const QRgb bumper = pixelAt(image, {1.15, 1.5});
  EXPECT_GT(qRed(bumper), 180);
  EXPECT_LT(qGreen(bumper), 90);
  // Somewhere on the ghost outline there is its green.
  bool green = false;
  const Pose2 truth = *s.true_pose;
  for (double t = -0.15; t <= 0.15 && !green; t += 0.005) {
    const QRgb c = pixelAt(image, truth.toWorld({t, 0.15}));
    green = qGreen(c) > qRed(c) + 40 && qGreen(c) > qBlue(c) + 20;
  }
  EXPECT_TRUE(green);
}

// Range from p along heading to the walls of the 4 m x 3 m room (no obstacles), for a scene.
double roomRange(const Vec2& p, double heading) {
  const double c = std::cos(heading), s = std::sin(heading);
  double t = 1e9;
  if (c > 1e-9)
    t = std::min(t, (4.0 - p.x()) / c);
  if (c < -1e-9)
    t = std::min(t, -p.x() / c);
  if (s > 1e-9)
    t = std::min(t, (3.0 - p.y()) / s);
  if (s < -1e-9)
    t = std::min(t, -p.y() / s);
  return t;
}

TEST_F(MapCanvasTest, FullSceneRendersWithEveryLayer) {
  // Raster underlay: the room's outline as a ROS map with a 5 cm cell, shifted 10 cm so it is
  // visible beside the vector walls.
  WorldMap map = smallRoom();
  RasterLayer layer;
  layer.source = "room.yaml";
  layer.raster.width = 84;
  layer.raster.height = 64;
  layer.raster.resolution_m = 0.05;
  layer.raster.origin = {-0.1, -0.1, 0.0};
  layer.raster.cells.assign(84 * 64, RasterMap::kFree);
  for (int c = 0; c < 84; ++c) {
    for (int r = 0; r < 64; ++r) {
      if (c < 2 || r < 2 || c >= 82 || r >= 62)
        layer.raster.at(c, r) = RasterMap::kOccupied;
      if (c >= 70 && r >= 50)
        layer.raster.at(c, r) = RasterMap::kUnknown;
    }
  }
  map.raster = layer;
  canvas.resize(800, 600);
  canvas.setWorldMap(map);

  OccupancyGrid grid(0.01);
  canvas.setGrid(&grid);
  const RobotProfile profile = squareRobot();
  const SonarInverseModel model;
  TelemetrySample s;
  for (int i = 0; i <= 120; ++i) {  // drive an arc through the room, mapping as we go
    const double a = i / 120.0 * kPi;
    s.time_s = i * 0.1;
    s.odometry_pose = {2.0 - 1.2 * std::cos(a), 0.8 + 0.9 * std::sin(a), wrapAngle(a - kPi / 2)};
    s.true_pose = Pose2{s.odometry_pose.x + 0.04 * std::sin(a), s.odometry_pose.y + 0.03,
                        s.odometry_pose.theta + 0.05};
    s.sonar.clear();
    for (int k = 0; k < 2; ++k) {
      const Pose2 mount =
          s.odometry_pose.compose(profile.sonars[static_cast<std::size_t>(k)].mount);
      const double range = roomRange(mount.position(), mount.theta);
      const bool echo = range < 2.5;
      s.sonar.push_back({k, echo ? range : 0.0, echo});
      grid.integrateSonar(mount.position(), mount.theta, degToRad(25.0), echo ? range : 4.0, echo,
                          model);
    }
    s.bumpers = i == 120 ? 1u : 0u;
    canvas.setRobotState(s);
    canvas.gridUpdated();
  }
  canvas.zoomToFit();
  const QImage image = render();
  saveScreenshot(image, "irgs_canvas_full.png");
  // The live grid shows the free space swept by the sonars (light blue-white over the floor).
  const QRgb swept = pixelAt(image, {2.0, 1.3});
  EXPECT_GT(qBlue(swept), qRed(swept) + 10);
  EXPECT_GT(canvas.trailSize(), 100u);
}

}  // namespace
}  // namespace irgs::widgets
