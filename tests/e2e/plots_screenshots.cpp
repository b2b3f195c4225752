// Photographs the plots and parameters docks for the docs: the simulated robot driving arcs on
// the default map for 60 s with the stereo-sonar EKF running, three plot panels (velocity
// against command, estimator error, two sonar ranges), then the parameters dock.
// Usage: plots_screenshots OUT_DIR (run under xvfb-run or offscreen).

#include <QApplication>
#include <QDir>
#include <QDockWidget>
#include <QEventLoop>
#include <QSettings>
#include <QTemporaryDir>
#include <QTextStream>
#include <QTimer>
#include <cmath>

#include "app/gui/localization_controller.hpp"
#include "app/gui/main_window.hpp"
#include "app/gui/parameters_controller.hpp"
#include "app/gui/plots_controller.hpp"
#include "app/gui/session_controller.hpp"
#include "core/robot/robot_profile_file.hpp"
#include "core/sim/gyro_sim.hpp"
#include "core/sim/sim_presets.hpp"
#include "core/sim/simulated_robot.hpp"
#include "core/world/map_file.hpp"
#include "widgets/canvas/map_canvas.hpp"
#include "widgets/plots/field_browser.hpp"
#include "widgets/plots/plot_panel.hpp"
#include "widgets/plots/plots_dock.hpp"

using namespace irgs;
using namespace irgs::gui;

namespace {

bool save(QApplication& app, MainWindow& window, const QString& path) {
  QEventLoop loop;
  QTimer::singleShot(300, &loop, &QEventLoop::quit);
  loop.exec();
  app.processEvents();
  const bool ok = window.grab().save(path);
  QTextStream(stdout) << (ok ? "wrote " : "FAILED ") << path << '\n';
  return ok;
}

}  // namespace

int main(int argc, char** argv) {
  QApplication app(argc, argv);
  if (argc != 2) {
    QTextStream(stderr) << "usage: plots_screenshots OUT_DIR\n";
    return 2;
  }
  const QString out = QString::fromLocal8Bit(argv[1]);
  QDir().mkpath(out);
  const std::string root = IRGS_SOURCE_DIR;
  RobotProfileResult robot = loadRobotProfileFile(root + "/resources/robots/thesis_robot.json");
  MapLoadResult map = loadMapFile(root + "/resources/maps/default.json");
  if (!robot.profile || !map.map)
    return 1;
  QTemporaryDir dir;
  QSettings settings(dir.filePath(QStringLiteral("s.ini")), QSettings::IniFormat);
  SessionController session(*robot.profile, [](const WorldMap& m, const RobotProfile& p) {
    // As the GUI's simulator: typical odometry errors and an AUTOGYRO-level gyro.
    SimConfig config = typicalSimConfig();
    config.gyro = autogyroErrorModel();
    config.seed = 1;
    return std::make_unique<SimulatedRobot>(m, p, config);
  });
  MainWindow window(session, settings);
  session.loadWorld(*map.map, QStringLiteral("default.json"));
  window.resize(1400, 950);
  window.show();
  window.localization().setEstimator(EstimatorKind::kStereoEkf);
  window.localization().dock().hide();
  PlotsController& plots = window.plots();
  plots.dock().show();
  widgets::PlotsDock& dock = plots.plots();

  // Loops of changing radius about the start, 60 s of robot time, at the GUI's tick.
  for (int i = 0; i < 3000; ++i) {
    const double t = i * 0.02;
    session.drive(0.12, 0.6 + 0.3 * std::sin(t * 0.3));
    session.tick(0.02);
    if (i % 10 == 0)
      app.processEvents();
  }
  session.stopRobot();
  while (dock.panelCount() < 3)
    dock.addPanel();
  dock.setWindow_s(60.0);
  dock.setCurrentPanel(&dock.panel(0));
  dock.plotFields({QStringLiteral("Telemetry/Velocity/angular"),
                   QStringLiteral("Command/Velocity/angular"),
                   QStringLiteral("Telemetry/Gyro/rate")});
  dock.setCurrentPanel(&dock.panel(1));
  dock.plotFields({QStringLiteral("Estimator/Error/position"), QStringLiteral("Estimator/Sigma/x"),
                   QStringLiteral("Estimator/Sigma/y")});
  dock.panel(1).setTraceScale(QStringLiteral("Estimator/Error/position"), 100.0,
                              QStringLiteral("cm"));
  dock.panel(1).setTraceScale(QStringLiteral("Estimator/Sigma/x"), 100.0, QStringLiteral("cm"));
  dock.panel(1).setTraceScale(QStringLiteral("Estimator/Sigma/y"), 100.0, QStringLiteral("cm"));
  dock.setCurrentPanel(&dock.panel(2));
  dock.plotFields(
      {QStringLiteral("Telemetry/Sonar/range 00"), QStringLiteral("Telemetry/Sonar/range 04")});
  auto& browser = dock.browser();
  for (const char* group : {"Telemetry/Velocity/angular", "Estimator/Error/position"}) {
    if (QTreeWidgetItem* item = browser.itemFor(QString::fromLatin1(group)))
      item->parent()->setExpanded(true);
  }
  window.resizeDocks({&plots.dock()}, {470}, Qt::Vertical);
  window.canvas().zoomToFit();
  dock.refreshNow();
  bool ok = save(app, window, out + QStringLiteral("/irgs-plots.png"));

  plots.dock().hide();
  window.parameters().dock().show();
  window.resize(1700, 950);
  window.resizeDocks({&window.parameters().dock()}, {640}, Qt::Horizontal);
  window.canvas().zoomToFit();
  ok = save(app, window, out + QStringLiteral("/irgs-parameters.png")) && ok;
  return ok ? 0 : 1;
}
