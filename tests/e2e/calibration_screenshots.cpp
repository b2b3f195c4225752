// Photographs the calibration wizards and the Drive tab's pad for docs/calibration.md and
// docs/teleop.md: the UMBmark wizard after a simulated run (injected E_d 1.01, E_b 1.03), the gyro
// wizard after the simulated AUTOGYRO procedure, the main window with the pad being dragged, and
// the editor after vectorising a raster of the default map.
// Usage: calibration_screenshots OUT_DIR (run under xvfb-run or offscreen).

#include <QApplication>
#include <QDir>
#include <QSettings>
#include <QTemporaryDir>
#include <QTest>
#include <QTextStream>

#include "app/gui/drive_input_controller.hpp"
#include "app/gui/editor_controller.hpp"
#include "app/gui/main_window.hpp"
#include "app/gui/session_controller.hpp"
#include "core/robot/robot_profile_file.hpp"
#include "core/sim/simulated_robot.hpp"
#include "core/world/map_file.hpp"
#include "core/world/raster_world.hpp"
#include "tests/e2e/app_test_support.hpp"
#include "widgets/calibration/gyro_wizard.hpp"
#include "widgets/calibration/umbmark_wizard.hpp"
#include "widgets/editor/editor_panel.hpp"
#include "widgets/teleop/drive_pad.hpp"

using namespace irgs;
using namespace irgs::gui;

namespace {

bool save(QWidget& widget, const QDir& dir, const QString& name) {
  const QString path = dir.filePath(name);
  if (!widget.grab().save(path)) {
    QTextStream(stderr) << "cannot write " << path << '\n';
    return false;
  }
  QTextStream(stdout) << "wrote " << path << '\n';
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  QApplication app(argc, argv);
  if (argc != 2) {
    QTextStream(stderr) << "usage: calibration_screenshots OUT_DIR\n";
    return 2;
  }
  const QDir out(QString::fromLocal8Bit(argv[1]));
  const std::string root = IRGS_SOURCE_DIR;
  RobotProfileResult p3dx = loadRobotProfileFile(root + "/resources/robots/pioneer_p3dx.json");
  RobotProfileResult thesis = loadRobotProfileFile(root + "/resources/robots/thesis_robot.json");
  MapLoadResult map = loadMapFile(root + "/resources/maps/default.json");
  if (!p3dx.profile || !thesis.profile || !map.map)
    return 1;
  QTemporaryDir dir;

  widgets::UmbmarkWizard umbmark(*p3dx.profile, dir.filePath(QStringLiteral("p3dx.json")));
  umbmark.setSeed(11);
  umbmark.show();
  umbmark.runSimulation();
  QTest::qWait(50);
  bool ok = save(umbmark, out, QStringLiteral("irgs-calibration-umbmark.png"));

  widgets::GyroWizard gyro(*p3dx.profile, dir.filePath(QStringLiteral("p3dx.json")));
  gyro.show();
  gyro.run();
  QTest::qWait(50);
  ok = save(gyro, out, QStringLiteral("irgs-calibration-gyro.png")) && ok;

  QSettings settings(dir.filePath(QStringLiteral("settings.ini")), QSettings::IniFormat);
  SessionController session(*thesis.profile, [](const WorldMap& m, const RobotProfile& p) {
    return std::unique_ptr<Robot>(std::make_unique<SimulatedRobot>(m, p));
  });
  MainWindow window(session, settings);
  session.loadWorld(*map.map, QStringLiteral("default.json"));
  DriveInputController input(window.commandPanel(), session, std::make_unique<test::NoGamepad>());
  window.resize(1500, 950);
  window.show();
  if (!QTest::qWaitForWindowExposed(&window))
    return 1;
  widgets::DrivePad& pad = input.pad();
  const QPoint centre(pad.width() / 2, pad.height() / 2);
  QTest::mousePress(&pad, Qt::LeftButton, {}, centre);
  QTest::mouseMove(&pad, centre + QPoint(pad.width() / 6, -pad.height() / 3));
  for (int i = 0; i < 100; ++i)
    session.tick(0.02);
  QTest::qWait(50);
  ok = save(window, out, QStringLiteral("irgs-drive-pad.png")) && ok;
  QTest::mouseRelease(&pad, Qt::LeftButton, {}, centre);

  // The editor after "Vectorise Raster to Walls" on a 5 cm raster of the default map's walls
  // and obstacles (as a ROS map of that flat would look).
  RasterMap raster;
  const Box2 box = map.map->bounds();
  raster.resolution_m = 0.05;
  raster.origin = Pose2{box.min.x() - 0.2, box.min.y() - 0.2, 0.0};
  raster.width = static_cast<int>((box.max.x() - box.min.x() + 0.4) / raster.resolution_m);
  raster.height = static_cast<int>((box.max.y() - box.min.y() + 0.4) / raster.resolution_m);
  raster.cells.assign(static_cast<std::size_t>(raster.width * raster.height), RasterMap::kFree);
  for (int row = 0; row < raster.height; ++row)
    for (int col = 0; col < raster.width; ++col) {
      const Vec2 p = raster.cellCentre(col, row);
      if (map.map->distanceToNearestSegment(p) < 0.06 || map.map->obstacleAt(p) != nullptr)
        raster.at(col, row) = RasterMap::kOccupied;
    }
  session.loadWorld(worldFromRaster(raster, "default_scan.yaml"), QStringLiteral("scan.yaml"));
  window.editor().setActive(true);
  window.editor().panel().vectoriseAction()->trigger();
  QTest::qWait(50);
  ok = save(window, out, QStringLiteral("irgs-editor-vectorise.png")) && ok;
  window.editor().shutdown();
  return ok ? 0 : 1;
}
