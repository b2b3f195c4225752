// The editor widgets offscreen: the model's undo stack, the tool layer driven by real mouse
// events on a canvas, and numeric editing in the property panel.

#include <gtest/gtest.h>

#include <QAction>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QLabel>
#include <QLineEdit>
#include <QListWidget>
#include <QSignalSpy>
#include <QTableWidget>
#include <QtTest/QTest>

#include "core/world/map_file.hpp"
#include "widgets/canvas/map_canvas.hpp"
#include "widgets/editor/editor_layer.hpp"
#include "widgets/editor/editor_model.hpp"
#include "widgets/editor/editor_panel.hpp"
#include "widgets/editor/property_panel.hpp"

namespace irgs::widgets {
namespace {

using editing::ElementKind;
using editing::ElementRef;

WorldMap room() {
  WorldMap map;
  map.name = "room";
  map.walls.push_back({"outer", {{0, 0}, {4, 0}, {4, 3}, {0, 3}}, true, {}});
  map.obstacles.push_back({"box", {{3.0, 0.5}, {3.5, 0.5}, {3.5, 1.0}, {3.0, 1.0}}, {}});
  map.start = Pose2{1.0, 1.5, 0.0};
  return map;
}

// A canvas at 100 px/m centred on the room, with the model and the layer on it.
struct Fixture {
  MapCanvas canvas;
  EditorModel model;
  EditorLayer* layer = nullptr;

  Fixture() {
    canvas.resize(800, 600);
    canvas.setWorldMap(room());
    canvas.setView(Vec2(2.0, 1.5), 100.0);
    model.setMap(room());
    layer = new EditorLayer(canvas, model);
    canvas.show();
    layer->show();
  }
  QPoint px(double x, double y) const { return canvas.worldToWidget(Vec2(x, y)).toPoint(); }
  void click(double x, double y, Qt::KeyboardModifiers mods = {}) {
    QTest::mouseClick(layer, Qt::LeftButton, mods, px(x, y));
  }
  void drag(Vec2 from, Vec2 to) {
    QTest::mousePress(layer, Qt::LeftButton, {}, px(from.x(), from.y()));
    const Vec2 mid = (from + to) / 2.0;
    QTest::mouseMove(layer, px(mid.x(), mid.y()));
    QTest::mouseMove(layer, px(to.x(), to.y()));
    QTest::mouseRelease(layer, Qt::LeftButton, {}, px(to.x(), to.y()));
  }
};

TEST(EditorModel, EveryEditIsUndoableAndRedoable) {
  EditorModel model;
  model.setMap(room());
  const std::string original = serializeMap(model.map());
  EXPECT_FALSE(model.isModified());
  ASSERT_TRUE(model.tryApply([](const WorldMap& m) {
    return editing::moveElements(m, {{ElementKind::kObstacle, 0}}, Vec2(0.5, 0.0));
  }));
  EXPECT_TRUE(model.isModified());
  EXPECT_EQ(model.selection(), (std::vector<ElementRef>{{ElementKind::kObstacle, 0}}));
  const std::string moved = serializeMap(model.map());
  model.undoStack().undo();
  EXPECT_EQ(serializeMap(model.map()), original);
  EXPECT_FALSE(model.isModified());
  model.undoStack().redo();
  EXPECT_EQ(serializeMap(model.map()), moved);
}

TEST(EditorModel, AnEditThatDoesNotFitIsRejectedWithAReason) {
  EditorModel model;
  model.setMap(room());
  QSignalSpy rejected(&model, &EditorModel::rejected);
  editing::Edit bad;
  bad.changes.push_back({ElementKind::kWall, 7, editing::Element(Wall{}), std::nullopt});
  EXPECT_FALSE(model.apply(bad));
  EXPECT_EQ(rejected.count(), 1);
  EXPECT_FALSE(model.tryApply([](const WorldMap& m) {
    return editing::addElement(m, Wall{"", {{0, 0}}, false, {}});
  }));
  EXPECT_EQ(rejected.count(), 2);
  EXPECT_EQ(model.undoStack().count(), 0);
}

TEST(EditorModel, CopyPasteAndDeleteActOnTheSelection) {
  EditorModel model;
  model.setMap(room());
  model.setSelection({{ElementKind::kObstacle, 0}, {ElementKind::kStart, 0}});
  model.copySelection();
  ASSERT_TRUE(model.canPaste());
  model.paste(Vec2(-2.0, 1.0));
  ASSERT_EQ(model.map().obstacles.size(), 2u);
  EXPECT_EQ(model.selection(), (std::vector<ElementRef>{{ElementKind::kObstacle, 1}}));
  model.deleteSelection();
  EXPECT_EQ(model.map().obstacles.size(), 1u);
  EXPECT_EQ(model.undoStack().count(), 2);
}

TEST(EditorLayer, DrawsASnappedWallWithClicksAndADoubleClick) {
  Fixture f;
  f.model.setSnapSettings({true, 0.1, false, 0.1, 0.0});
  f.layer->setTool(EditorTool::kWall);
  f.click(0.52, 0.48);  // -> (0.5, 0.5)
  f.click(1.98, 0.53);  // -> (2.0, 0.5)
  f.click(2.03, 1.21);  // -> (2.0, 1.2)
  EXPECT_EQ(f.layer->draftPoints().size(), 3u);
  QTest::mouseDClick(f.layer, Qt::LeftButton, {}, f.px(2.03, 1.21));
  ASSERT_EQ(f.model.map().walls.size(), 2u);
  const Wall& w = f.model.map().walls[1];
  ASSERT_EQ(w.points.size(), 3u);
  EXPECT_NEAR(w.points[0].x(), 0.5, 1e-9);
  EXPECT_NEAR(w.points[0].y(), 0.5, 1e-9);
  EXPECT_NEAR(w.points[1].x(), 2.0, 1e-9);
  EXPECT_NEAR(w.points[2].y(), 1.2, 1e-9);
  EXPECT_FALSE(w.closed);
  EXPECT_TRUE(f.layer->draftPoints().empty());
}

TEST(EditorLayer, ClickingTheFirstPointClosesTheOutlineAndEndpointsSnap) {
  Fixture f;
  f.model.setSnapSettings({false, 0.1, true, 0.1, 0.0});
  f.layer->setTool(EditorTool::kWall);
  f.click(4.03, 3.02);  // 3 px from the room corner (4, 3): snaps onto it
  f.click(5.0, 3.0);
  f.click(5.0, 2.0);
  f.click(4.02, 3.01);  // the first point: closes
  ASSERT_EQ(f.model.map().walls.size(), 2u);
  const Wall& w = f.model.map().walls[1];
  EXPECT_TRUE(w.closed);
  ASSERT_EQ(w.points.size(), 3u);
  EXPECT_EQ(w.points[0], Vec2(4.0, 3.0));
}

TEST(EditorLayer, AngleSnapHoldsTheDirectionToTheStep) {
  Fixture f;
  f.model.setSnapSettings({true, 0.1, false, 0.1, degToRad(45.0)});
  f.layer->setTool(EditorTool::kWall);
  f.click(1.0, 1.0);
  f.click(1.0 + 1.0, 1.0 + 0.8);  // 38.7 degrees -> 45, length 1.28 -> 1.3
  QTest::keyClick(f.layer, Qt::Key_Return);
  ASSERT_EQ(f.model.map().walls.size(), 2u);
  const Vec2 d = f.model.map().walls[1].points[1] - f.model.map().walls[1].points[0];
  EXPECT_NEAR(std::atan2(d.y(), d.x()), degToRad(45.0), 1e-9);
  EXPECT_NEAR(d.norm(), 1.3, 1e-9);
}

TEST(EditorLayer, SelectDragMovesTheElementByItsSnappedVertexAndUndoRestores) {
  Fixture f;
  f.model.setSnapSettings({true, 0.25, false, 0.1, 0.0});
  const std::string before = serializeMap(f.model.map());
  // Grab the box near its corner (3, 0.5) and drag 0.98 m left, 1.03 m up: (2, 1.5) on the grid.
  f.drag(Vec2(3.02, 0.52), Vec2(2.04, 1.55));
  EXPECT_EQ(f.model.selection(), (std::vector<ElementRef>{{ElementKind::kObstacle, 0}}));
  const auto& poly = f.model.map().obstacles[0].polygon;
  EXPECT_NEAR(poly[0].x(), 2.0, 1e-9);
  EXPECT_NEAR(poly[0].y(), 1.5, 1e-9);
  f.model.undoStack().undo();
  EXPECT_EQ(serializeMap(f.model.map()), before);
}

TEST(EditorLayer, RubberBandSelectsAndDeleteKeyDeletes) {
  Fixture f;
  f.drag(Vec2(2.8, 0.3), Vec2(3.7, 1.7));  // box and nothing else
  EXPECT_EQ(f.model.selection(), (std::vector<ElementRef>{{ElementKind::kObstacle, 0}}));
  QTest::keyClick(f.layer, Qt::Key_Delete);
  EXPECT_TRUE(f.model.map().obstacles.empty());
}

TEST(EditorLayer, StartPoseToolSetsPositionAndSnappedHeading) {
  Fixture f;
  f.model.setSnapSettings({true, 0.1, false, 0.1, degToRad(15.0)});
  f.layer->setTool(EditorTool::kStart);
  f.drag(Vec2(2.01, 2.02), Vec2(2.01 + 0.5, 2.02 + 0.3));  // 31 degrees -> 30
  EXPECT_NEAR(f.model.map().start.x, 2.0, 1e-9);
  EXPECT_NEAR(f.model.map().start.y, 2.0, 1e-9);
  EXPECT_NEAR(f.model.map().start.theta, degToRad(30.0), 1e-9);
}

TEST(EditorLayer, MeasureReportsDistanceAndHeading) {
  Fixture f;
  f.model.setSnapSettings({true, 0.1, false, 0.1, 0.0});
  f.layer->setTool(EditorTool::kMeasure);
  QSignalSpy measured(f.layer, &EditorLayer::measured);
  f.drag(Vec2(0.0, 0.0), Vec2(3.0, 4.0));
  ASSERT_EQ(measured.count(), 1);
  EXPECT_NEAR(measured.at(0).at(0).toDouble(), 5.0, 1e-9);
  EXPECT_NEAR(measured.at(0).at(1).toDouble(), std::atan2(4.0, 3.0), 1e-9);
  EXPECT_EQ(f.model.undoStack().count(), 0);  // measuring changes nothing
}

TEST(EditorLayer, FeatureToolsPlaceCornersAndEdges) {
  Fixture f;
  f.model.setSnapSettings({true, 0.5, false, 0.1, 0.0});
  f.layer->setTool(EditorTool::kCorner);
  f.click(3.9, 2.9);
  f.layer->setTool(EditorTool::kEdge);
  f.click(1.1, 0.1);
  ASSERT_EQ(f.model.map().features.size(), 2u);
  EXPECT_EQ(f.model.map().features[0].kind, PointFeatureKind::kCorner);
  EXPECT_EQ(f.model.map().features[0].position, Vec2(4.0, 3.0));
  EXPECT_EQ(f.model.map().features[1].kind, PointFeatureKind::kEdge);
  EXPECT_EQ(f.model.map().features[1].position, Vec2(1.0, 0.0));
}

TEST(PropertyPanel, NumericEditsBecomeUndoableEditsAndBadValuesAreRefused) {
  EditorModel model;
  model.setMap(room());
  PropertyPanel panel(model);
  model.setSelection({{ElementKind::kStart, 0}});
  panel.xSpin()->setValue(2.5);
  panel.headingSpin()->setValue(90.0);
  EXPECT_DOUBLE_EQ(model.map().start.x, 2.5);
  EXPECT_NEAR(model.map().start.theta, kPi / 2.0, 1e-12);
  EXPECT_EQ(model.undoStack().count(), 2);

  model.setSelection({{ElementKind::kObstacle, 0}});
  ASSERT_EQ(panel.vertexTable()->rowCount(), 4);
  panel.vertexTable()->item(0, 0)->setText(QStringLiteral("2.75"));
  EXPECT_DOUBLE_EQ(model.map().obstacles[0].polygon[0].x(), 2.75);
  panel.vertexTable()->item(0, 1)->setText(QStringLiteral("abc"));
  EXPECT_FALSE(panel.errorLabel()->text().isEmpty());
  EXPECT_DOUBLE_EQ(model.map().obstacles[0].polygon[0].y(), 0.5);

  model.setSelection({{ElementKind::kWall, 0}});
  panel.idEdit()->setText(QStringLiteral("box"));  // taken by the obstacle
  emit panel.idEdit()->editingFinished();
  EXPECT_EQ(model.map().walls[0].id, "outer");
  EXPECT_FALSE(panel.errorLabel()->text().isEmpty());

  panel.applyMove(1.0, 0.0);
  EXPECT_DOUBLE_EQ(model.map().walls[0].points[0].x(), 1.0);
}

TEST(EditorPanel, SnapControlsAndActionsDriveTheModel) {
  Fixture f;
  EditorPanel panel(f.model, *f.layer);
  panel.gridStep().setValue(0.5);
  panel.angleCombo().setCurrentIndex(1);  // 15 degrees
  EXPECT_DOUBLE_EQ(f.model.snapSettings().grid_step_m, 0.5);
  EXPECT_NEAR(f.model.snapSettings().angle_step_rad, degToRad(15.0), 1e-12);
  panel.toolAction(EditorTool::kPolygon)->trigger();
  EXPECT_EQ(f.layer->tool(), EditorTool::kPolygon);
  f.model.setSelection({{ElementKind::kObstacle, 0}});
  panel.copyAction()->trigger();
  panel.pasteAction()->trigger();
  EXPECT_EQ(f.model.map().obstacles.size(), 2u);
  panel.undoAction()->trigger();
  EXPECT_EQ(f.model.map().obstacles.size(), 1u);
  panel.redoAction()->trigger();
  EXPECT_EQ(f.model.map().obstacles.size(), 2u);
  // An issue (the pasted copy overlaps nothing; put the start on a wall) is listed.
  f.model.tryApply([](const WorldMap& m) { return editing::setStart(m, Pose2{0.02, 1.5, 0}); });
  EXPECT_GE(panel.issueList().count(), 1);
}

}  // namespace
}  // namespace irgs::widgets
