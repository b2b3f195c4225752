// The map editor in the main window, offscreen (issue 6 item 1): draw with snapping, move,
// undo/redo, numeric editing, save, reload and compare the saved file; the simulator runs on the
// edited map; unsaved-changes protection; autosave to the recovery file.

#include <gtest/gtest.h>

#include <QAction>
#include <QApplication>
#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFile>
#include <QListWidget>
#include <QSettings>
#include <QSignalSpy>
#include <QTabWidget>
#include <QTemporaryDir>
#include <QTest>
#include <nlohmann/json.hpp>

#include "app/gui/editor_controller.hpp"
#include "app/gui/main_window.hpp"
#include "app/gui/map_file_actions.hpp"
#include "app/gui/session_controller.hpp"
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

std::string readText(const QString& path) {
  return readFile(path.toStdString()).bytes;
}

class EditorGuiTest : public ::testing::Test {
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
    canvas().setView(Vec2(0.0, 0.0), 100.0);  // the 3 m room fills 300 px
  }
  void TearDown() override { qunsetenv("IRGS_RECOVERY_DIR"); }

  EditorController& editor() { return window_->editor(); }
  widgets::EditorModel& model() { return editor().model(); }
  widgets::EditorLayer& layer() { return editor().layer(); }
  widgets::EditorPanel& panel() { return editor().panel(); }
  widgets::MapCanvas& canvas() { return window_->canvas(); }
  void click(double x, double y) { test::clickAt(layer(), canvas(), x, y); }

  // Grid 0.1 m, endpoints, 90 degree angles; then the scripted drawing of two walls.
  void drawTwoWalls() {
    panel().gridCheck().setChecked(true);
    panel().gridStep().setValue(0.1);
    panel().endpointCheck().setChecked(true);
    panel().angleCombo().setCurrentIndex(3);  // 90 degrees
    panel().toolAction(EditorTool::kWall)->trigger();
    click(-1.47, 0.52);  // grid: (-1.5, 0.5), on the room's west wall
    click(0.03, 0.58);   // 90 degrees from the anchor, 1.5 m: (0, 0.5)
    QTest::keyClick(&layer(), Qt::Key_Return);
    click(0.06, 0.44);   // within 10 px of (0, 0.5): the endpoint, not the grid's (0.1, 0.4)
    click(0.02, -0.83);  // straight down from the anchor, 1.3 m: (0, -0.8)
    QTest::mouseDClick(&layer(), Qt::LeftButton, {}, test::toPixel(canvas(), 0.02, -0.83));
  }

  QTemporaryDir dir_;
  QString map_path_;
  std::unique_ptr<QSettings> settings_;
  std::unique_ptr<SessionController> session_;
  std::unique_ptr<MainWindow> window_;
};

TEST_F(EditorGuiTest, TheEditTabShowsTheToolLayerOverTheCanvas) {
  EXPECT_TRUE(layer().isVisible());
  EXPECT_EQ(layer().size(), canvas().size());
  window_->controlTabs().setCurrentIndex(0);
  EXPECT_FALSE(editor().isActive());
  EXPECT_FALSE(layer().isVisible());
  window_->controlTabs().setCurrentWidget(&panel());
  EXPECT_TRUE(editor().isActive());
}

TEST_F(EditorGuiTest, DrawSnapMoveUndoRedoSaveAndReloadGiveTheExpectedFile) {
  drawTwoWalls();
  ASSERT_EQ(model().map().walls.size(), 3u);
  const Wall& a = model().map().walls[1];
  const Wall& b = model().map().walls[2];
  ASSERT_EQ(a.points.size(), 2u);
  ASSERT_EQ(b.points.size(), 2u);
  EXPECT_NEAR(a.points[0].x(), -1.5, 1e-9);
  EXPECT_NEAR(a.points[1].x(), 0.0, 1e-9);
  EXPECT_NEAR(a.points[1].y(), 0.5, 1e-9);
  EXPECT_EQ(b.points[0], a.points[1]);  // joined exactly by the endpoint snap
  EXPECT_NEAR(b.points[1].x(), 0.0, 1e-9);
  EXPECT_NEAR(b.points[1].y(), -0.8, 1e-9);

  // Move the first new wall: grab it near its west end (it moves by that end, (-1.5, 0.5)),
  // drop it about 0.3 m right and 0.4 m up; the end snaps to the grid point (-1.2, 0.9).
  panel().toolAction(EditorTool::kSelect)->trigger();
  test::dragFromTo(layer(), canvas(), Vec2(-0.9, 0.5), Vec2(-0.9 + 0.31, 0.5 + 0.42));
  ASSERT_EQ(model().selection(), (std::vector<ElementRef>{{ElementKind::kWall, 1}}));
  EXPECT_NEAR(model().map().walls[1].points[0].x(), -1.2, 1e-9);
  EXPECT_NEAR(model().map().walls[1].points[0].y(), 0.9, 1e-9);
  EXPECT_NEAR(model().map().walls[1].points[1].x(), 0.3, 1e-9);

  // Undo the move, redo it.
  panel().undoAction()->trigger();
  EXPECT_NEAR(model().map().walls[1].points[0].x(), -1.5, 1e-9);
  panel().redoAction()->trigger();
  EXPECT_NEAR(model().map().walls[1].points[0].x(), -1.2, 1e-9);

  // Numeric editing: select the start pose and turn it to 90 degrees.
  click(0.0, 0.0);
  ASSERT_EQ(model().selection(), (std::vector<ElementRef>{{ElementKind::kStart, 0}}));
  panel().properties().headingSpin()->setValue(90.0);
  EXPECT_NEAR(model().map().start.theta, kPi / 2.0, 1e-12);
  EXPECT_EQ(model().undoStack().count(), 4);  // two walls, move, heading

  // The simulator runs on the edited map without saving.
  auto* robot = dynamic_cast<SimulatedRobot*>(session_->robot());
  ASSERT_NE(robot, nullptr);
  EXPECT_EQ(robot->simulator().map().walls.size(), 3u);
  EXPECT_EQ(serializeMap(session_->worldMap()), serializeMap(model().map()));
  EXPECT_TRUE(editor().isModified());

  // Save through the File menu's action, compare with the same edits made by the core.
  ASSERT_TRUE(window_->mapFiles().save());
  EXPECT_FALSE(editor().isModified());
  WorldMap expected = test::squareRoom();
  Wall wa;
  wa.id = "wall-1";
  wa.points = {Vec2(-1.2, 0.9), Vec2(0.3, 0.9)};
  Wall wb;
  wb.id = "wall-2";
  wb.points = {Vec2(0.0, 0.5), Vec2(0.0, -0.8)};
  expected.walls.push_back(wa);
  expected.walls.push_back(wb);
  expected.start.theta = kPi / 2.0;
  const std::string saved = readText(map_path_);
  const std::string difference = test::jsonDifference(
      nlohmann::json::parse(saved), nlohmann::json::parse(serializeMap(expected)));
  EXPECT_EQ(difference, "") << saved;

  // Reload: the same map, a clean document.
  ASSERT_TRUE(window_->mapFiles().openMap(map_path_));
  EXPECT_EQ(serializeMap(model().map()), saved);
  EXPECT_EQ(serializeMap(session_->worldMap()), saved);
  EXPECT_FALSE(editor().isModified());
  EXPECT_EQ(model().undoStack().count(), 0);
}

TEST_F(EditorGuiTest, PolygonObstacleAndValidationMarkersFollowTheEdits) {
  panel().gridStep().setValue(0.1);
  panel().angleCombo().setCurrentIndex(0);
  panel().toolAction(EditorTool::kPolygon)->trigger();
  click(-0.2, -0.2);
  click(0.2, -0.2);
  click(0.2, 0.2);
  click(-0.2, 0.2);
  click(-0.2, -0.2);  // the first point closes the polygon
  ASSERT_EQ(model().map().obstacles.size(), 1u);
  // The start pose (0, 0) is now inside the obstacle: an error on the canvas and in the list.
  ASSERT_FALSE(model().issues().empty());
  EXPECT_EQ(model().issues().front().kind, editing::IssueKind::kStartInWall);
  EXPECT_GE(panel().issueList().count(), 1);
  panel().undoAction()->trigger();
  EXPECT_TRUE(model().issues().empty());
}

TEST_F(EditorGuiTest, TheEditTabDoesNotForceTheWindowTallerThanALaptopScreen) {
  // A 1366 x 768 screen less the task bar and the title bar leaves about 700 px. The Edit
  // page at its fullest (a polygon selected: the property panel lists its vertices; the
  // validation list filled) scrolls instead of setting the window's minimum height.
  panel().toolAction(EditorTool::kPolygon)->trigger();
  click(-0.2, -0.2);
  click(0.2, -0.2);
  click(0.2, 0.2);
  click(-0.2, 0.2);
  click(-0.2, -0.2);
  ASSERT_EQ(model().map().obstacles.size(), 1u);
  model().setSelection({{ElementKind::kObstacle, 0}});
  ASSERT_FALSE(model().issues().empty());
  QApplication::processEvents();
  const QSize minimum = window_->minimumSizeHint().expandedTo(window_->minimumSize());
  EXPECT_LE(minimum.height(), 700);
  EXPECT_LE(minimum.width(), 1366);
}

TEST_F(EditorGuiTest, UnsavedEditsBlockOpeningAndClosingUntilDiscarded) {
  panel().toolAction(EditorTool::kCorner)->trigger();
  click(1.5, 1.5);
  ASSERT_TRUE(editor().isModified());
  editor().setUnsavedPolicy(EditorController::UnsavedPolicy::kCancel);
  EXPECT_FALSE(window_->mapFiles().openMap(map_path_));
  EXPECT_EQ(model().map().features.size(), 1u);
  EXPECT_FALSE(window_->close());
  EXPECT_TRUE(window_->isVisible());
  editor().setUnsavedPolicy(EditorController::UnsavedPolicy::kDiscard);
  EXPECT_TRUE(window_->mapFiles().openMap(map_path_));
  EXPECT_TRUE(model().map().features.empty());
  EXPECT_FALSE(editor().isModified());
}

TEST_F(EditorGuiTest, AutosaveWritesTheRecoveryFileAndUndoingToCleanRemovesIt) {
  editor().setAutosaveInterval(0.05);
  QSignalSpy autosaved(&editor(), &EditorController::autosaved);
  EXPECT_FALSE(editor().autosaveNow());  // nothing unsaved
  drawTwoWalls();
  ASSERT_TRUE(QTest::qWaitFor([&] { return autosaved.count() > 0; }, 5000));
  const QString recovery = editor().recoveryFile();
  ASSERT_TRUE(QFile::exists(recovery));
  const nlohmann::json saved = nlohmann::json::parse(readText(recovery));
  EXPECT_EQ(saved["walls"].size(), 3u);
  EXPECT_EQ(saved[EditorController::kRecoveryKey]["source"].get<std::string>(),
            QFileInfo(map_path_).absoluteFilePath().toStdString());
  // No temporary files are left beside it (the write is atomic: temp + rename).
  EXPECT_EQ(QDir(QFileInfo(recovery).absolutePath()).entryList(QDir::Files).size(), 1);
  model().undoStack().setIndex(0);  // back to the saved state
  EXPECT_FALSE(QFile::exists(recovery));
}

}  // namespace
}  // namespace irgs::gui
