// Photographs the camera dock on the bundled default map for docs/landmark-navigation.md: the
// simulated robot at its start below the living-room marker and light, the rendered frame, the
// top view and the detections. Usage: camera_screenshot OUT.png (offscreen or under xvfb-run).

#include <QApplication>
#include <QDockWidget>
#include <QEventLoop>
#include <QSettings>
#include <QTemporaryDir>
#include <QTest>
#include <QTextStream>
#include <QTimer>

#include "app/gui/camera_controller.hpp"
#include "app/gui/main_window.hpp"
#include "app/gui/session_controller.hpp"
#include "core/robot/robot_profile_file.hpp"
#include "core/sim/simulated_robot.hpp"
#include "core/world/map_file.hpp"
#include "widgets/canvas/map_canvas.hpp"

using namespace irgs;
using namespace irgs::gui;

int main(int argc, char** argv) {
  QApplication app(argc, argv);
  if (argc != 2) {
    QTextStream(stderr) << "usage: camera_screenshot OUT.png\n";
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
  window.restoreSettings(QSize(1500, 950));
  window.resize(1500, 950);
  window.camera().setMinWallPeriodMs(0);  // the program ticks faster than real time
  window.camera().dock().show();
  window.resizeDocks({&window.camera().dock()}, {380}, Qt::Vertical);
  window.show();
  if (!QTest::qWaitForWindowExposed(&window))
    return 1;
  window.canvas().zoomToFit();
  // Half a second forward towards the living-room marker.
  session.drive(0.2, 0.0);
  for (int i = 0; i < 10; ++i)
    session.tick(0.05);
  session.stopRobot();
  QEventLoop loop;
  QTimer::singleShot(300, &loop, &QEventLoop::quit);
  loop.exec();
  const QString out = QString::fromLocal8Bit(argv[1]);
  const bool ok = window.grab().save(out);
  if (!ok)
    QTextStream(stderr) << "cannot write " << out << "\n";
  return ok ? 0 : 1;
}
