// Photographs the map editor on the bundled default map for docs/gui.md: the Edit tab with a
// selected obstacle in the property panel, a wall being drawn with the angle snap showing, a
// measurement, and a validation marker (a wall stopping short of another).
// Usage: editor_screenshot OUT.png (run under xvfb-run or offscreen).

#include <QAction>
#include <QApplication>
#include <QEventLoop>
#include <QSettings>
#include <QTemporaryDir>
#include <QTest>
#include <QTextStream>
#include <QTimer>

#include "app/gui/editor_controller.hpp"
#include "app/gui/main_window.hpp"
#include "app/gui/session_controller.hpp"
#include "core/robot/robot_profile_file.hpp"
#include "core/sim/simulated_robot.hpp"
#include "core/world/map_file.hpp"
#include "widgets/canvas/map_canvas.hpp"
#include "widgets/editor/editor_layer.hpp"
#include "widgets/editor/editor_model.hpp"
#include "widgets/editor/editor_panel.hpp"

using namespace irgs;
using namespace irgs::gui;

int main(int argc, char** argv) {
  QApplication app(argc, argv);
  if (argc != 2) {
    QTextStream(stderr) << "usage: editor_screenshot OUT.png\n";
    return 2;
  }
  const std::string root = IRGS_SOURCE_DIR;
  RobotProfileResult robot = loadRobotProfileFile(root + "/resources/robots/thesis_robot.json");
  MapLoadResult map = loadMapFile(root + "/resources/maps/default.json");
  if (!robot.profile || !map.map)
    return 1;
  QTemporaryDir dir;
  qputenv("IRGS_RECOVERY_DIR", dir.filePath(QStringLiteral("recovery")).toUtf8());
  QSettings settings(dir.filePath(QStringLiteral("s.ini")), QSettings::IniFormat);
  SessionController session(*robot.profile, [](const WorldMap& m, const RobotProfile& p) {
    SimConfig config;
    config.seed = 1;
    return std::make_unique<SimulatedRobot>(m, p, config);
  });
  MainWindow window(session, settings);
  session.loadWorld(*map.map, QStringLiteral("default.json"));
  window.restoreSettings(QSize(1400, 860));
  window.resize(1400, 860);
  window.show();
  if (!QTest::qWaitForWindowExposed(&window))
    return 1;
  EditorController& editor = window.editor();
  editor.setActive(true);
  widgets::MapCanvas& canvas = window.canvas();
  canvas.zoomToFit();
  app.processEvents();
  widgets::EditorLayer& layer = editor.layer();
  widgets::EditorModel& model = editor.model();
  auto px = [&](double x, double y) { return canvas.worldToWidget(Vec2(x, y)).toPoint(); };

  // A partition that stops 15 cm short of the outer wall: a validation warning.
  model.tryApply([](const WorldMap& m) {
    Wall wall;
    wall.points = {Vec2(3.3, 2.3), Vec2(3.3, 3.35)};
    return editing::addElement(m, wall);
  });
  // A measurement across the living room.
  layer.setTool(widgets::EditorTool::kMeasure);
  QTest::mousePress(&layer, Qt::LeftButton, {}, px(0.0, 2.4));
  QTest::mouseMove(&layer, px(2.6, 2.4));
  QTest::mouseRelease(&layer, Qt::LeftButton, {}, px(2.6, 2.4));
  // The selected desk in the property panel (selection drawn with handles).
  for (std::size_t i = 0; i < model.map().obstacles.size(); ++i) {
    if (model.map().obstacles[i].id == "desk")
      model.setSelection({{editing::ElementKind::kObstacle, i}});
  }
  // A wall being drawn with the 45 degree snap, the cursor past its second point.
  layer.setTool(widgets::EditorTool::kWall);
  QTest::mouseClick(&layer, Qt::LeftButton, {}, px(5.6, 1.0));
  QTest::mouseClick(&layer, Qt::LeftButton, {}, px(5.6, 2.2));
  QTest::mouseMove(&layer, px(6.3, 2.85));

  QEventLoop loop;
  QTimer::singleShot(300, &loop, &QEventLoop::quit);
  loop.exec();
  const QString out = QString::fromLocal8Bit(argv[1]);
  const bool ok = window.grab().save(out);
  QTextStream(stdout) << (ok ? "wrote " : "FAILED ") << out << '\n';
  editor.shutdown();
  return ok ? 0 : 1;
}
