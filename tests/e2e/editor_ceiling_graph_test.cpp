// The map editor's ceiling and graph tools in the main window, offscreen (issue 6 item 1, issue 7
// item 1): place markers, a light, nodes tied to markers and edges through the tool layer with
// snapping; move, rotate, copy/paste, delete, undo/redo; numeric editing in the property panel;
// the simulator runs on the edits; save, reload and compare the saved file with the same map
// built by the core.

#include <gtest/gtest.h>

#include <QAction>
#include <QCheckBox>
#include <QComboBox>
#include <QDir>
#include <QDoubleSpinBox>
#include <QFile>
#include <QFileInfo>
#include <QImage>
#include <QLabel>
#include <QLineEdit>
#include <QSettings>
#include <QTemporaryDir>
#include <QTest>
#include <nlohmann/json.hpp>

#include "app/gui/editor_controller.hpp"
#include "app/gui/main_window.hpp"
#include "app/gui/map_file_actions.hpp"
#include "app/gui/session_controller.hpp"
#include "core/editing/floor_plan.hpp"
#include "core/io/atomic_file.hpp"
#include "core/sim/simulated_robot.hpp"
#include "core/world/map_file.hpp"
#include "tests/e2e/app_test_support.hpp"
#include "tests/e2e/editor_test_support.hpp"
#include "widgets/canvas/map_canvas.hpp"
#include "widgets/editor/editor_layer.hpp"
#include "widgets/editor/editor_model.hpp"
#include "widgets/editor/editor_panel.hpp"
#include "widgets/editor/property_panel.hpp"

namespace irgs::gui {
namespace {

using editing::ElementKind;
using editing::ElementRef;
using widgets::EditorTool;

class EditorCeilingGraphTest : public ::testing::Test {
 protected:
  void SetUp() override {
    test::ensureApp();
    ASSERT_TRUE(dir_.isValid());
    qputenv("IRGS_RECOVERY_DIR", dir_.filePath(QStringLiteral("recovery")).toUtf8());
    map_path_ = dir_.filePath(QStringLiteral("room.json"));
    ASSERT_FALSE(saveMapFile(test::squareRoom(), map_path_.toStdString()));
    settings_ = std::make_unique<QSettings>(dir_.filePath(QStringLiteral("settings.ini")),
                                            QSettings::IniFormat);
    session_ = std::make_unique<SessionController>(test::thesisRobot(), test::simulatedFactory());
    window_ = std::make_unique<MainWindow>(*session_, *settings_);
    window_->restoreSettings(QSize(1200, 800));
    ASSERT_TRUE(window_->mapFiles().openMap(map_path_));
    window_->show();
    ASSERT_TRUE(QTest::qWaitForWindowExposed(window_.get()));
    editor().setActive(true);
    canvas().setView(Vec2(0.0, 0.0), 100.0);  // 100 px per metre
    panel().gridCheck().setChecked(true);
    panel().gridStep().setValue(0.1);
    panel().endpointCheck().setChecked(true);
    panel().angleCombo().setCurrentIndex(3);  // 90 degrees
  }
  void TearDown() override { qunsetenv("IRGS_RECOVERY_DIR"); }

  EditorController& editor() { return window_->editor(); }
  widgets::EditorModel& model() { return editor().model(); }
  widgets::EditorLayer& layer() { return editor().layer(); }
  widgets::EditorPanel& panel() { return editor().panel(); }
  widgets::PropertyPanel& properties() { return panel().properties(); }
  widgets::MapCanvas& canvas() { return window_->canvas(); }
  const WorldMap& map() { return model().map(); }
  void click(double x, double y) { test::clickAt(layer(), canvas(), x, y); }
  void drag(Vec2 from, Vec2 to) { test::dragFromTo(layer(), canvas(), from, to); }

  // Two markers, a light between them, three nodes (two tied to the markers), two edges.
  void placeCeilingAndGraph() {
    panel().toolAction(EditorTool::kCeilingMarker)->trigger();
    drag({-1.02, 0.48}, {-1.0, 1.0});  // centre on the grid (-1, 0.5), heading up: 90 degrees
    click(1.03, 0.47);                 // a click: heading 0
    panel().toolAction(EditorTool::kCeilingLight)->trigger();
    drag({-0.61, 0.52}, {0.58, 0.55});  // (-0.6, 0.5) to 1.2 m along 0 degrees
    panel().toolAction(EditorTool::kGraphNode)->trigger();
    click(-0.95, 0.55);  // on marker-1: the node goes to its centre, tied to it
    click(1.04, 0.45);   // on marker-2
    click(1.02, -0.79);  // free floor: the grid point (1, -0.8)
    panel().toolAction(EditorTool::kGraphEdge)->trigger();
    click(-1.0, 0.5);
    click(1.0, 0.5);
    click(1.0, 0.5);
    click(1.0, -0.8);
  }

  QTemporaryDir dir_;
  QString map_path_;
  std::unique_ptr<QSettings> settings_;
  std::unique_ptr<SessionController> session_;
  std::unique_ptr<MainWindow> window_;
};

TEST_F(EditorCeilingGraphTest, ToolsPlaceSnappedMarkersLightNodesAndEdges) {
  placeCeilingAndGraph();
  ASSERT_EQ(map().markers.size(), 2u);
  EXPECT_EQ(map().markers[0].id, "marker-1");
  EXPECT_TRUE(map().markers[0].position.isApprox(Vec2(-1.0, 0.5)));
  EXPECT_NEAR(map().markers[0].heading_rad, kPi / 2.0, 1e-12);
  EXPECT_TRUE(map().markers[1].position.isApprox(Vec2(1.0, 0.5)));
  EXPECT_NEAR(map().markers[1].heading_rad, 0.0, 1e-12);
  ASSERT_EQ(map().lights.size(), 1u);
  EXPECT_TRUE(map().lights[0].tube.a.isApprox(Vec2(-0.6, 0.5)));
  EXPECT_TRUE(map().lights[0].tube.b.isApprox(Vec2(0.6, 0.5)));
  ASSERT_EQ(map().graph.nodes.size(), 3u);
  EXPECT_EQ(map().graph.nodes[0].marker_id, "marker-1");
  EXPECT_TRUE(map().graph.nodes[0].position.isApprox(Vec2(-1.0, 0.5)));
  EXPECT_EQ(map().graph.nodes[1].marker_id, "marker-2");
  EXPECT_EQ(map().graph.nodes[2].marker_id, "");
  EXPECT_TRUE(map().graph.nodes[2].position.isApprox(Vec2(1.0, -0.8)));
  ASSERT_EQ(map().graph.edges.size(), 2u);
  EXPECT_EQ(map().graph.edges[0].from, "node-1");
  EXPECT_EQ(map().graph.edges[0].to, "node-2");
  EXPECT_EQ(map().graph.edges[1].from, "node-2");
  EXPECT_EQ(map().graph.edges[1].to, "node-3");
  EXPECT_TRUE(model().issues().empty());
  EXPECT_EQ(model().undoStack().count(), 8);  // one step per placed element

  // An edge repeating one is refused with a message and changes nothing.
  click(1.0, 0.5);
  click(-1.0, 0.5);
  EXPECT_EQ(map().graph.edges.size(), 2u);
  EXPECT_NE(properties().errorLabel()->text().indexOf(QStringLiteral("already joined")), -1);

  // Undo everything, redo everything: the same map.
  const std::string placed = serializeMap(map());
  model().undoStack().setIndex(0);
  EXPECT_TRUE(map().markers.empty());
  EXPECT_TRUE(map().graph.nodes.empty());
  model().undoStack().setIndex(8);
  EXPECT_EQ(serializeMap(map()), placed);
}

TEST_F(EditorCeilingGraphTest, MoveEditCopyDeleteUndoThenSaveAndReloadGiveTheExpectedFile) {
  placeCeilingAndGraph();

  // Drag marker-2 by its square (off the node at its centre) 0.3 m up: its node goes along.
  panel().toolAction(EditorTool::kSelect)->trigger();
  drag({1.07, 0.43}, {1.07, 0.74});
  ASSERT_EQ(model().selection(), (std::vector<ElementRef>{{ElementKind::kMarker, 1}}));
  EXPECT_TRUE(map().markers[1].position.isApprox(Vec2(1.0, 0.8)));
  EXPECT_TRUE(map().graph.nodes[1].position.isApprox(Vec2(1.0, 0.8)));
  panel().undoAction()->trigger();
  EXPECT_TRUE(map().graph.nodes[1].position.isApprox(Vec2(1.0, 0.5)));
  panel().redoAction()->trigger();
  EXPECT_TRUE(map().graph.nodes[1].position.isApprox(Vec2(1.0, 0.8)));

  // The light: width and length in the property panel (about its centre).
  click(0.0, 0.51);
  ASSERT_EQ(model().selection(), (std::vector<ElementRef>{{ElementKind::kLight, 0}}));
  properties().widthSpin()->setValue(0.15);
  properties().sizeSpin()->setValue(1.0);
  EXPECT_NEAR(map().lights[0].width_m, 0.15, 1e-12);
  EXPECT_TRUE(map().lights[0].tube.a.isApprox(Vec2(-0.5, 0.5)));
  EXPECT_TRUE(map().lights[0].tube.b.isApprox(Vec2(0.5, 0.5)));

  // The node-2 - node-3 edge: a given corridor length.
  click(1.0, -0.2);
  ASSERT_EQ(model().selection(), (std::vector<ElementRef>{{ElementKind::kEdge, 1}}));
  EXPECT_NE(properties().costLabel()->text().indexOf(QStringLiteral("1.600 m")), -1);
  properties().costGivenCheck()->setChecked(true);
  properties().costSpin()->setValue(2.5);
  EXPECT_EQ(map().graph.edges[1].cost_m, std::optional<double>(2.5));

  // Marker-1: rotate back to heading 0, then a colour.
  click(-1.07, 0.43);
  ASSERT_EQ(model().selection(), (std::vector<ElementRef>{{ElementKind::kMarker, 0}}));
  properties().applyRotate(-90.0);
  EXPECT_NEAR(map().markers[0].heading_rad, 0.0, 1e-12);
  properties().colourEdit()->setText(QStringLiteral("#00ff00"));
  emit properties().colourEdit()->editingFinished();
  EXPECT_EQ(map().markers[0].colour, (ColourRgb{0, 255, 0}));
  properties().colourEdit()->setText(QStringLiteral("green"));
  emit properties().colourEdit()->editingFinished();
  EXPECT_FALSE(properties().errorLabel()->text().isEmpty());
  EXPECT_EQ(map().markers[0].colour, (ColourRgb{0, 255, 0}));

  // Copy and paste the marker with its node: the copy's node is tied to the copied marker.
  click(-1.0, 0.5);  // node-1 (over the marker's centre)
  ASSERT_EQ(model().selection(), (std::vector<ElementRef>{{ElementKind::kNode, 0}}));
  model().setSelection({{ElementKind::kMarker, 0}, {ElementKind::kNode, 0}});
  panel().copyAction()->trigger();
  panel().pasteAction()->trigger();
  ASSERT_EQ(map().markers.size(), 3u);
  ASSERT_EQ(map().graph.nodes.size(), 4u);
  EXPECT_EQ(map().graph.nodes[3].marker_id, map().markers[2].id);
  EXPECT_TRUE(map().markers[2].position.isApprox(Vec2(-0.9, 0.4)));
  panel().undoAction()->trigger();
  EXPECT_EQ(map().markers.size(), 2u);

  // Delete node-3: its edge goes too; undo brings both back.
  click(1.0, -0.8);
  ASSERT_EQ(model().selection(), (std::vector<ElementRef>{{ElementKind::kNode, 2}}));
  panel().deleteAction()->trigger();
  EXPECT_EQ(map().graph.nodes.size(), 2u);
  EXPECT_EQ(map().graph.edges.size(), 1u);
  panel().undoAction()->trigger();
  EXPECT_EQ(map().graph.edges.size(), 2u);
  EXPECT_TRUE(model().issues().empty());

  // The simulator runs on the edited map without saving.
  auto* robot = dynamic_cast<SimulatedRobot*>(session_->robot());
  ASSERT_NE(robot, nullptr);
  EXPECT_EQ(robot->simulator().map().markers.size(), 2u);
  EXPECT_EQ(robot->simulator().map().graph.edges.size(), 2u);
  EXPECT_EQ(serializeMap(session_->worldMap()), serializeMap(map()));

  // Save and compare with the same map built by the core.
  ASSERT_TRUE(window_->mapFiles().save());
  WorldMap expected = test::squareRoom();
  CeilingMarker m1;
  m1.id = "marker-1";
  m1.position = {-1.0, 0.5};
  m1.colour = {0, 255, 0};
  CeilingMarker m2;
  m2.id = "marker-2";
  m2.position = {1.0, 0.8};
  expected.markers = {m1, m2};
  CeilingLight light;
  light.id = "light-1";
  light.tube = {{-0.5, 0.5}, {0.5, 0.5}};
  light.width_m = 0.15;
  expected.lights = {light};
  TopoNode n1, n2, n3;
  n1.id = "node-1";
  n1.position = {-1.0, 0.5};
  n1.marker_id = "marker-1";
  n2.id = "node-2";
  n2.position = {1.0, 0.8};
  n2.marker_id = "marker-2";
  n3.id = "node-3";
  n3.position = {1.0, -0.8};
  expected.graph.nodes = {n1, n2, n3};
  TopoEdge e1, e2;
  e1.from = "node-1";
  e1.to = "node-2";
  e2.from = "node-2";
  e2.to = "node-3";
  e2.cost_m = 2.5;
  expected.graph.edges = {e1, e2};
  const std::string saved = readFile(map_path_.toStdString()).bytes;
  EXPECT_EQ(test::jsonDifference(nlohmann::json::parse(saved),
                                 nlohmann::json::parse(serializeMap(expected))),
            "")
      << saved;

  // Reload: the same map, a clean document.
  ASSERT_TRUE(window_->mapFiles().openMap(map_path_));
  EXPECT_EQ(serializeMap(map()), saved);
  EXPECT_FALSE(editor().isModified());
  EXPECT_EQ(map().graph.edges[1].cost_m, std::optional<double>(2.5));
}

TEST_F(EditorCeilingGraphTest, TyingRenamingAndDraggingALightEndThroughThePanelAndHandles) {
  placeCeilingAndGraph();
  panel().toolAction(EditorTool::kSelect)->trigger();

  // Tie the free node-3 to marker-2 in the panel: it jumps onto the marker's centre.
  click(1.0, -0.8);
  ASSERT_EQ(model().selection(), (std::vector<ElementRef>{{ElementKind::kNode, 2}}));
  QComboBox* markers = properties().markerCombo();
  ASSERT_EQ(markers->count(), 3);  // (none), marker-1, marker-2
  markers->setCurrentIndex(markers->findData(QStringLiteral("marker-2")));
  EXPECT_EQ(map().graph.nodes[2].marker_id, "marker-2");
  EXPECT_TRUE(map().graph.nodes[2].position.isApprox(Vec2(1.0, 0.5)));
  panel().undoAction()->trigger();
  EXPECT_TRUE(map().graph.nodes[2].position.isApprox(Vec2(1.0, -0.8)));

  // Rename node-2: both of its edges follow; a taken id is refused in red.
  click(1.0, 0.5);
  ASSERT_EQ(model().selection(), (std::vector<ElementRef>{{ElementKind::kNode, 1}}));
  properties().idEdit()->setText(QStringLiteral("junction"));
  emit properties().idEdit()->editingFinished();
  EXPECT_EQ(map().graph.edges[0].to, "junction");
  EXPECT_EQ(map().graph.edges[1].from, "junction");
  properties().idEdit()->setText(QStringLiteral("node-1"));
  emit properties().idEdit()->editingFinished();
  EXPECT_EQ(map().graph.nodes[1].id, "junction");
  EXPECT_FALSE(properties().errorLabel()->text().isEmpty());

  // Select the light, then drag its east end handle 0.3 m north: it turns and lengthens.
  click(0.0, 0.5);
  ASSERT_EQ(model().selection(), (std::vector<ElementRef>{{ElementKind::kLight, 0}}));
  drag({0.6, 0.5}, {0.61, 0.79});
  EXPECT_TRUE(map().lights[0].tube.a.isApprox(Vec2(-0.6, 0.5)));
  EXPECT_TRUE(map().lights[0].tube.b.isApprox(Vec2(0.6, 0.8)));
  EXPECT_NEAR(properties().headingSpin()->value(), radToDeg(std::atan2(0.3, 1.2)),
              0.05);  // the panel shows the new orientation
  EXPECT_TRUE(model().issues().empty());
}

TEST_F(EditorCeilingGraphTest, AFloorPlanIsOpenedCalibratedByTwoClicksSavedAndReloaded) {
  // A 200 x 100 px drawing in a folder beside the map's.
  ASSERT_TRUE(QDir(dir_.path()).mkdir(QStringLiteral("plans")));
  const QString image_path = dir_.filePath(QStringLiteral("plans/plan.png"));
  QImage drawing(200, 100, QImage::Format_RGB32);
  drawing.fill(Qt::white);
  ASSERT_TRUE(drawing.save(image_path));
  EXPECT_FALSE(panel().openFloorPlan(dir_.filePath(QStringLiteral("nope.png"))).isEmpty());
  ASSERT_EQ(panel().openFloorPlan(image_path), QString());
  ASSERT_TRUE(map().floor_plan);
  EXPECT_EQ(layer().tool(), EditorTool::kCalibrate);
  // 2 cm per pixel, the image's top-left corner at the map's (-1.5, 1.5).
  EXPECT_NEAR(map().floor_plan->metres_per_pixel, 0.02, 1e-12);
  EXPECT_TRUE(map().floor_plan->origin.isApprox(Vec2(-1.5, 1.5)));
  const FloorPlan opened = *map().floor_plan;

  // Click image pixel (50, 50), now at (-0.5, 0.5): the panel offers that as A's position.
  const Vec2 a_now = editing::floorPlanToWorld(opened, {50, 50});
  click(a_now.x(), a_now.y());
  EXPECT_NEAR(panel().calibrationX().value(), -0.5, 0.01);
  EXPECT_NEAR(panel().calibrationY().value(), 0.5, 0.01);
  // A is truly at the origin and B, pixel (150, 50), 3 m from it.
  panel().calibrationX().setValue(0.0);
  panel().calibrationY().setValue(0.0);
  panel().calibrationDistance().setValue(3.0);
  const Vec2 b_now = editing::floorPlanToWorld(opened, {150, 50});
  click(b_now.x(), b_now.y());
  ASSERT_TRUE(map().floor_plan);
  const FloorPlan calibrated = *map().floor_plan;
  // Clicks land on whole screen pixels (half an image pixel here): 1 % on the scale.
  EXPECT_NEAR(calibrated.metres_per_pixel, 0.03, 0.0003);
  EXPECT_NEAR(calibrated.rotation_rad, 0.0, 0.01);
  EXPECT_LT(editing::floorPlanToWorld(calibrated, {50, 50}).norm(), 0.02);
  EXPECT_NEAR(editing::floorPlanToWorld(calibrated, {150, 50}).x(), 3.0, 0.04);
  panel().undoAction()->trigger();
  EXPECT_EQ(*map().floor_plan, opened);
  panel().redoAction()->trigger();
  EXPECT_EQ(*map().floor_plan, calibrated);
  panel().floorPlanOpacity().setValue(0.3);
  EXPECT_EQ(map().floor_plan->opacity, 0.3);

  // Saved relative to the map file (atomically, with the rest), reloaded the same.
  ASSERT_TRUE(window_->mapFiles().save());
  const nlohmann::json saved = nlohmann::json::parse(readFile(map_path_.toStdString()).bytes);
  EXPECT_EQ(saved["floor_plan"]["source"].get<std::string>(), "plans/plan.png");
  EXPECT_NEAR(saved["floor_plan"]["metres_per_pixel"].get<double>(), calibrated.metres_per_pixel,
              1e-12);
  EXPECT_EQ(saved["floor_plan"]["opacity"].get<double>(), 0.3);
  ASSERT_TRUE(window_->mapFiles().openMap(map_path_));
  ASSERT_TRUE(map().floor_plan);
  EXPECT_EQ(map().floor_plan->resolved_path,
            QFileInfo(image_path).absoluteFilePath().toStdString());
  EXPECT_NEAR(map().floor_plan->metres_per_pixel, calibrated.metres_per_pixel, 1e-12);
  EXPECT_FALSE(editor().isModified());

  // Remove, undo.
  panel().removeFloorPlanAction()->trigger();
  EXPECT_FALSE(map().floor_plan);
  panel().undoAction()->trigger();
  EXPECT_TRUE(map().floor_plan);

  // Crash recovery brings a plan back, found by its absolute path (a plan opened anew is
  // referenced by its file name alone until the map is saved).
  ASSERT_EQ(panel().openFloorPlan(image_path), QString());
  const FloorPlan reopened = *map().floor_plan;
  ASSERT_TRUE(editor().autosaveNow());
  const QString recovery = dir_.filePath(
      QStringLiteral("recovery/%1").arg(QString::fromLatin1(EditorController::kRecoveryFileName)));
  const QString kept = dir_.filePath(QStringLiteral("kept-recovery.json"));
  ASSERT_TRUE(QFile::copy(recovery, kept));
  while (editor().isModified())  // back to the saved plan, as a restarted app opens the map
    panel().undoAction()->trigger();
  EXPECT_EQ(map().floor_plan->metres_per_pixel, calibrated.metres_per_pixel);
  QFile::remove(recovery);
  ASSERT_TRUE(QFile::copy(kept, recovery));
  editor().setRecoveryPolicy(EditorController::RecoveryPolicy::kAccept);
  ASSERT_TRUE(editor().offerRecovery());
  ASSERT_TRUE(map().floor_plan);
  EXPECT_EQ(map().floor_plan->metres_per_pixel, reopened.metres_per_pixel);
  EXPECT_EQ(map().floor_plan->resolved_path,
            QFileInfo(image_path).absoluteFilePath().toStdString());
  panel().undoAction()->trigger();  // the recovery is one undoable step
  EXPECT_EQ(map().floor_plan->metres_per_pixel, calibrated.metres_per_pixel);
}

}  // namespace
}  // namespace irgs::gui
