// Photographs the three planning modes of the window on the bundled default map, for the docs
// and for looking at: goal preview (raw A* vs amended path), a coverage run in progress, map
// building in progress. Usage: planning_screenshots OUT_DIR (run under xvfb-run or offscreen).

#include <QApplication>
#include <QDir>
#include <QEventLoop>
#include <QSettings>
#include <QTabWidget>
#include <QTemporaryDir>
#include <QTextStream>
#include <QTimer>
#include <functional>

#include "app/gui/behaviour_controller.hpp"
#include "app/gui/main_window.hpp"
#include "app/gui/planning_controller.hpp"
#include "app/gui/session_controller.hpp"
#include "core/robot/robot_profile_file.hpp"
#include "core/sim/simulated_robot.hpp"
#include "core/world/map_file.hpp"
#include "widgets/canvas/map_canvas.hpp"
#include "widgets/planning/planning_panel.hpp"

using namespace irgs;
using namespace irgs::gui;

namespace {

void runFor(QApplication& app, SessionController& session, double robot_s,
            const std::function<bool()>& done = {}) {
  session.setSpeedFactor(0.0);
  const double until = session.robotTime_s() + robot_s;
  while (session.robotTime_s() < until && !(done && done())) {
    session.tick(0.02);
    app.processEvents();
  }
  session.setSpeedFactor(1.0);
  app.processEvents();
}

bool save(MainWindow& window, const QString& path) {
  // Let the console's batched lines and the status bar's timer catch up first.
  QEventLoop loop;
  QTimer::singleShot(300, &loop, &QEventLoop::quit);
  loop.exec();
  const bool ok = window.grab().save(path);
  QTextStream(stdout) << (ok ? "wrote " : "FAILED ") << path << '\n';
  return ok;
}

}  // namespace

int main(int argc, char** argv) {
  QApplication app(argc, argv);
  if (argc != 2) {
    QTextStream(stderr) << "usage: planning_screenshots OUT_DIR\n";
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
    SimConfig config;
    config.seed = 1;
    return std::make_unique<SimulatedRobot>(m, p, config);
  });
  MainWindow window(session, settings);
  session.loadWorld(*map.map, QStringLiteral("default.json"));
  window.restoreSettings(QSize(1280, 800));
  window.resize(1280, 800);
  window.show();
  window.controlTabs().setCurrentWidget(&window.planningPanel());
  runFor(app, session, 1.0);
  window.canvas().zoomToFit();
  bool ok = true;

  // 1. Goal preview: the raw A* path beside the amended one.
  window.planningPanel().setCurrentTab(widgets::PlanningPanel::Tab::kGoal);
  window.planningPanel().setPickGoalChecked(true);
  window.canvas().setInteraction(widgets::MapCanvas::Interaction::kPickGoal);
  window.planning().planGoal(Vec2(7.0, 3.1));
  runFor(app, session, 0.3);
  ok = save(window, out + QStringLiteral("/irgs-goal.png")) && ok;
  window.planning().driveGoal();
  runFor(app, session, 300.0, [&] { return !window.planning().behaviours().running(); });
  ok = save(window, out + QStringLiteral("/irgs-goal-driven.png")) && ok;

  // 2. Coverage of a region of the living room, about two thirds done.
  session.resetRobotToStart();
  window.canvas().setInteraction(widgets::MapCanvas::Interaction::kNavigate);
  window.planningPanel().setCurrentTab(widgets::PlanningPanel::Tab::kCoverage);
  window.planning().planRegion([] {
    Box2 box;
    box.extend(Vec2(2.4, 1.2));
    box.extend(Vec2(4.0, 3.1));
    return box;
  }());
  window.planning().driveCoverage();
  runFor(app, session, 600.0, [&] {
    return !window.planning().behaviours().running() ||
           window.planning().coverage().value_or(0.0) > 0.7;
  });
  ok = save(window, out + QStringLiteral("/irgs-coverage.png")) && ok;
  window.planning().stopAll(QStringLiteral("screenshot taken"));

  // 3. Map building from the start pose.
  session.resetRobotToStart();
  session.resetGrid();
  window.canvas().clearTrail();
  window.planningPanel().setCurrentTab(widgets::PlanningPanel::Tab::kMapBuilding);
  window.planning().startMapBuilding();
  runFor(app, session, 240.0, [&] { return !window.planning().behaviours().running(); });
  ok = save(window, out + QStringLiteral("/irgs-mapbuild.png")) && ok;
  window.planning().stopAll(QStringLiteral("screenshot taken"));
  return ok ? 0 : 1;
}
