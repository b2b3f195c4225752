// Photographs the map editor on the bundled default map for docs/gui.md: the Edit tab with a
// selected obstacle in the property panel, a wall being drawn with the angle snap showing, a
// measurement, and a validation marker (a wall stopping short of another). With --ceiling: the
// bundled delivery floor (paper 002) with a marker, its node and an edge placed by the tools, the
// new edge in the property panel and a second edge being drawn.
// Usage: editor_screenshot [--ceiling] OUT.png (run under xvfb-run or offscreen).

#include <QAction>
#include <QApplication>
#include <QDoubleSpinBox>
#include <QEventLoop>
#include <QImage>
#include <QPainter>
#include <QSettings>
#include <QTemporaryDir>
#include <QTest>
#include <QTextStream>
#include <QTimer>
#include <algorithm>

#include "app/gui/editor_controller.hpp"
#include "app/gui/main_window.hpp"
#include "app/gui/session_controller.hpp"
#include "core/editing/floor_plan.hpp"
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
  const bool ceiling = argc == 3 && QString::fromLocal8Bit(argv[1]) == QStringLiteral("--ceiling");
  if (argc != 2 && !ceiling) {
    QTextStream(stderr) << "usage: editor_screenshot [--ceiling] OUT.png\n";
    return 2;
  }
  const std::string root = IRGS_SOURCE_DIR;
  RobotProfileResult robot = loadRobotProfileFile(root + "/resources/robots/thesis_robot.json");
  MapLoadResult map = loadMapFile(root + (ceiling ? "/resources/maps/delivery_floor_002.json"
                                                  : "/resources/maps/default.json"));
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
  session.loadWorld(*map.map,
                    QString::fromLatin1(ceiling ? "delivery_floor_002.json" : "default.json"));
  const QSize size(1400, ceiling ? 1000 : 860);  // with a floor plan the Edit tab is taller
  window.restoreSettings(size);
  window.resize(size);
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
  if (ceiling) {
    // A floor-plan drawing of the same floor (drawn here from the map's walls at 5 cm per pixel,
    // as an architect's export would be), opened at the default 2 cm per pixel and calibrated
    // with the Calibrate tool: two wall corners 18.5 m apart.
    const double res = 0.05, x0 = -0.5, y1 = 12.0;  // the drawing's top-left corner in metres
    QImage drawing(int(21.0 / res), int(13.0 / res), QImage::Format_RGB32);
    drawing.fill(QColor(252, 250, 244));
    {
      QPainter d(&drawing);
      d.setRenderHint(QPainter::Antialiasing);
      auto img = [&](const Vec2& w) { return QPointF((w.x() - x0) / res, (y1 - w.y()) / res); };
      d.setPen(QPen(QColor(70, 70, 90), 3.0));
      for (const Segment& seg : model.map().segments())
        d.drawLine(img(seg.a), img(seg.b));
      QFont f = d.font();
      f.setPixelSize(9);
      d.setFont(f);
      d.setPen(QColor(90, 90, 120));
      d.drawText(img(Vec2(3.0, 5.0)), QStringLiteral("OFFICES"));
      d.drawText(img(Vec2(3.2, 10.9)), QStringLiteral("CORRIDOR B"));
      d.drawText(img(Vec2(8.3, 8.0)), QStringLiteral("HALL"));
      d.drawText(img(Vec2(12.0, 0.9)), QStringLiteral("CORRIDOR A   18.5 m"));
    }
    const QString plan_path = dir.filePath(QStringLiteral("floor_plan.png"));
    drawing.save(plan_path);
    widgets::EditorPanel& panel = editor.panel();
    if (!panel.openFloorPlan(plan_path).isEmpty())
      return 1;
    canvas.zoomToFit();
    app.processEvents();
    const FloorPlan opened = *model.map().floor_plan;
    const Vec2 a = editing::floorPlanToWorld(opened, {(0.5 - x0) / res, (y1 - 0.5) / res});
    const Vec2 b = editing::floorPlanToWorld(opened, {(19.0 - x0) / res, (y1 - 0.5) / res});
    QTest::mouseClick(&layer, Qt::LeftButton, {}, px(a.x(), a.y()));
    panel.calibrationX().setValue(0.5);
    panel.calibrationY().setValue(0.5);
    panel.calibrationDistance().setValue(18.5);
    QTest::mouseClick(&layer, Qt::LeftButton, {}, px(b.x(), b.y()));

    canvas.setView(Vec2(6.0, 7.0), 78.0);
    app.processEvents();
    // A new marker at (4.5, 10) heading along the corridor, a node on it, an edge from node 6.
    layer.setTool(widgets::EditorTool::kCeilingMarker);
    QTest::mousePress(&layer, Qt::LeftButton, {}, px(4.5, 10.0));
    QTest::mouseMove(&layer, px(4.9, 10.0));
    QTest::mouseRelease(&layer, Qt::LeftButton, {}, px(5.2, 10.0));
    layer.setTool(widgets::EditorTool::kGraphNode);
    QTest::mouseClick(&layer, Qt::LeftButton, {}, px(4.53, 10.03));
    layer.setTool(widgets::EditorTool::kGraphEdge);
    QTest::mouseClick(&layer, Qt::LeftButton, {}, px(2.0, 10.0));
    QTest::mouseClick(&layer, Qt::LeftButton, {}, px(4.5, 10.0));
    // The next edge being drawn from node 5, the cursor on its way.
    QTest::mouseClick(&layer, Qt::LeftButton, {}, px(8.0, 5.75));
    QTest::mouseMove(&layer, px(5.6, 7.9));

  } else {
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
  }

  QEventLoop loop;
  QTimer::singleShot(300, &loop, &QEventLoop::quit);
  loop.exec();
  const QString out = QString::fromLocal8Bit(argv[argc - 1]);
  const bool ok = window.grab().save(out);
  QTextStream(stdout) << (ok ? "wrote " : "FAILED ") << out << '\n';
  editor.shutdown();
  return ok ? 0 : 1;
}
