// The map editor's "Vectorise Raster to Walls" offscreen (issue 6 item 1): a ROS map opened in
// the main window is traced into closed walls in one undoable step, the simulator's map gets
// them, and they survive a save (as IRGS JSON, still referencing the raster) and reload.

#include <gtest/gtest.h>

#include <QAction>
#include <QSettings>
#include <QTemporaryDir>
#include <QtTest/QTest>
#include <memory>

#include "app/gui/editor_controller.hpp"
#include "app/gui/main_window.hpp"
#include "app/gui/map_file_actions.hpp"
#include "app/gui/session_controller.hpp"
#include "core/world/map_file.hpp"
#include "core/world/ros_map.hpp"
#include "tests/e2e/app_test_support.hpp"
#include "widgets/editor/editor_model.hpp"
#include "widgets/editor/editor_panel.hpp"

namespace irgs::gui {
namespace {

// A 4 m x 3 m room at 5 cm: a wall 3 cells thick around a free floor, one pillar inside.
RasterMap roomRaster() {
  RasterMap r;
  r.width = 80;
  r.height = 60;
  r.resolution_m = 0.05;
  r.origin = Pose2{-2.0, -1.5, 0.0};
  r.cells.assign(static_cast<std::size_t>(r.width * r.height), RasterMap::kOccupied);
  for (int row = 3; row < r.height - 3; ++row)
    for (int col = 3; col < r.width - 3; ++col)
      r.at(col, row) = RasterMap::kFree;
  for (int row = 28; row < 34; ++row)
    for (int col = 50; col < 56; ++col)
      r.at(col, row) = RasterMap::kOccupied;
  return r;
}

TEST(EditorVectorise, ARosMapIsTracedIntoWallsUndoablyAndTheWallsAreSaved) {
  test::ensureApp();
  QTemporaryDir dir;
  ASSERT_TRUE(dir.isValid());
  qputenv("IRGS_RECOVERY_DIR", dir.filePath(QStringLiteral("recovery")).toUtf8());
  const QString yaml = dir.filePath(QStringLiteral("room.yaml"));
  ASSERT_FALSE(saveRosMap(roomRaster(), yaml.toStdString()).has_value());
  QSettings settings(dir.filePath(QStringLiteral("settings.ini")), QSettings::IniFormat);
  SessionController session(test::thesisRobot(), test::simulatedFactory());
  auto window = std::make_unique<MainWindow>(session, settings);
  ASSERT_TRUE(window->mapFiles().openMap(yaml));
  window->show();
  ASSERT_TRUE(QTest::qWaitForWindowExposed(window.get()));
  EditorController& editor = window->editor();
  editor.setActive(true);
  widgets::EditorModel& model = editor.model();
  ASSERT_TRUE(model.map().raster.has_value());
  const std::size_t walls_before = model.map().walls.size();
  QAction* vectorise = editor.panel().vectoriseAction();
  ASSERT_TRUE(vectorise->isEnabled());

  vectorise->trigger();
  const auto& walls = model.map().walls;
  // The room's outer face, its inner face and the pillar.
  ASSERT_EQ(walls.size(), walls_before + 3);
  for (std::size_t i = walls_before; i < walls.size(); ++i) {
    EXPECT_TRUE(walls[i].closed);
    EXPECT_EQ(walls[i].points.size(), 4u);
  }
  EXPECT_EQ(model.selection().size(), 3u);
  EXPECT_EQ(session.worldMap().walls.size(), walls_before + 3);  // the simulator runs on it
  bool found_inner = false;  // the inner face of the room wall: x from -1.85 to 1.85
  for (std::size_t i = walls_before; i < walls.size(); ++i)
    for (const Vec2& p : walls[i].points)
      if (std::abs(p.x() + 1.85) < 1e-9 && std::abs(p.y() + 1.35) < 1e-9)
        found_inner = true;
  EXPECT_TRUE(found_inner);

  model.undoStack().undo();
  EXPECT_EQ(model.map().walls.size(), walls_before);
  model.undoStack().redo();
  ASSERT_EQ(model.map().walls.size(), walls_before + 3);

  const QString saved = dir.filePath(QStringLiteral("room.json"));
  // (File > Save of a ROS map asks for a JSON name in a dialog; the core writer is what it uses.)
  ASSERT_FALSE(saveMapFile(model.map(), saved.toStdString()).has_value());
  const MapLoadResult reloaded = loadMapFile(saved.toStdString());
  ASSERT_TRUE(reloaded.map.has_value());
  EXPECT_EQ(reloaded.map->walls.size(), walls_before + 3);
  EXPECT_TRUE(reloaded.map->raster.has_value());  // the raster layer stays, referenced
  editor.shutdown();
  window.reset();
  qunsetenv("IRGS_RECOVERY_DIR");
}

// A ROS map imported under an existing vector map (File > Open of a JSON map, then the Edit
// tab's import): one undoable step; vectorising it then adds its walls beside the old ones.
TEST(EditorVectorise, ARosMapImportedUnderAJsonMapIsAnUndoableRasterLayer) {
  test::ensureApp();
  QTemporaryDir dir;
  ASSERT_TRUE(dir.isValid());
  qputenv("IRGS_RECOVERY_DIR", dir.filePath(QStringLiteral("recovery")).toUtf8());
  const QString yaml = dir.filePath(QStringLiteral("scan.yaml"));
  ASSERT_FALSE(saveRosMap(roomRaster(), yaml.toStdString()).has_value());
  const QString json = dir.filePath(QStringLiteral("room.json"));
  ASSERT_FALSE(saveMapFile(test::squareRoom(), json.toStdString()).has_value());
  QSettings settings(dir.filePath(QStringLiteral("settings.ini")), QSettings::IniFormat);
  SessionController session(test::thesisRobot(), test::simulatedFactory());
  auto window = std::make_unique<MainWindow>(session, settings);
  ASSERT_TRUE(window->mapFiles().openMap(json));
  window->show();
  ASSERT_TRUE(QTest::qWaitForWindowExposed(window.get()));
  EditorController& editor = window->editor();
  editor.setActive(true);
  widgets::EditorModel& model = editor.model();
  widgets::EditorPanel& panel = editor.panel();
  ASSERT_FALSE(model.map().raster.has_value());
  EXPECT_FALSE(panel.vectoriseAction()->isEnabled());  // nothing to vectorise yet

  EXPECT_FALSE(panel.importRaster(dir.filePath(QStringLiteral("missing.yaml"))).isEmpty());
  EXPECT_FALSE(model.isModified());
  EXPECT_EQ(panel.importRaster(yaml), QString());
  ASSERT_TRUE(model.map().raster.has_value());
  EXPECT_EQ(model.map().raster->raster.width, 80);
  EXPECT_TRUE(session.worldMap().raster.has_value());  // the simulator sees it
  EXPECT_TRUE(model.isModified());
  EXPECT_TRUE(panel.vectoriseAction()->isEnabled());
  const std::size_t walls = model.map().walls.size();
  panel.vectoriseAction()->trigger();
  EXPECT_EQ(model.map().walls.size(), walls + 3);

  model.undoStack().undo();  // the walls
  model.undoStack().undo();  // the import
  EXPECT_FALSE(model.map().raster.has_value());
  EXPECT_EQ(model.map().walls.size(), walls);
  EXPECT_FALSE(panel.vectoriseAction()->isEnabled());
  model.undoStack().redo();
  ASSERT_TRUE(model.map().raster.has_value());

  // Saved as JSON, the raster is referenced relative to the map and loads again.
  const QString saved = dir.filePath(QStringLiteral("with_raster.json"));
  ASSERT_FALSE(saveMapFile(model.map(), saved.toStdString()).has_value());
  const MapLoadResult reloaded = loadMapFile(saved.toStdString());
  ASSERT_TRUE(reloaded.map.has_value());
  ASSERT_TRUE(reloaded.map->raster.has_value());
  EXPECT_EQ(reloaded.map->raster->raster.width, 80);
  editor.shutdown();
  window.reset();
  qunsetenv("IRGS_RECOVERY_DIR");
}

}  // namespace
}  // namespace irgs::gui
