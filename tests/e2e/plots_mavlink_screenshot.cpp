// Photographs the plots dock's MAVLink branch for docs/gui.md: the GUI linked to irgs-robot over
// a pty, driving loops for ~25 s, then LOCAL_POSITION_NED x/y, ATTITUDE yaw and one sonar's
// DISTANCE_SENSOR range plotted from the raw messages, the browser opened on them.
// Usage: plots_mavlink_screenshot OUT_DIR (run under xvfb-run).

#include <QApplication>
#include <QDir>
#include <QDockWidget>
#include <QElapsedTimer>
#include <QEventLoop>
#include <QSettings>
#include <QTemporaryDir>
#include <QTextStream>
#include <QTimer>
#include <QTreeWidgetItem>
#include <cmath>

#include "app/gui/link_controller.hpp"
#include "app/gui/link_ui.hpp"
#include "app/gui/main_window.hpp"
#include "app/gui/plots_controller.hpp"
#include "app/gui/session_controller.hpp"
#include "core/robot/robot_profile_file.hpp"
#include "core/sim/simulated_robot.hpp"
#include "core/world/map_file.hpp"
#include "tests/e2e/child_process.hpp"
#include "widgets/canvas/map_canvas.hpp"
#include "widgets/plots/field_browser.hpp"
#include "widgets/plots/plot_panel.hpp"
#include "widgets/plots/plots_dock.hpp"

using namespace irgs;
using namespace irgs::gui;

namespace {

void pump(QApplication& app, int ms) {
  QEventLoop loop;
  QTimer::singleShot(ms, &loop, &QEventLoop::quit);
  loop.exec();
  app.processEvents();
}

}  // namespace

int main(int argc, char** argv) {
  QApplication app(argc, argv);
  if (argc != 2) {
    QTextStream(stderr) << "usage: plots_mavlink_screenshot OUT_DIR\n";
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
  const std::string pty_link = dir.filePath(QStringLiteral("robot")).toStdString();
  irgs::test::ChildProcess firmware({IRGS_ROBOT_EXE, "--link", pty_link, "--baud", "115200",
                                     "--map", root + "/resources/maps/default.json", "--seed",
                                     "2"});
  if (!firmware.readLine(irgs::test::Clock::now() + std::chrono::seconds(30)))
    return 1;

  QSettings settings(dir.filePath(QStringLiteral("s.ini")), QSettings::IniFormat);
  SessionController session(*robot.profile, [](const WorldMap& m, const RobotProfile& p) {
    return std::make_unique<SimulatedRobot>(m, p, SimConfig{});
  });
  MainWindow window(session, settings);
  session.loadWorld(*map.map, QStringLiteral("default.json"));
  window.resize(1400, 1000);
  window.show();
  PlotsController& plots = window.plots();
  plots.dock().show();
  session.start();
  LinkController& link = window.linkUi().controller();
  const QString problem =
      link.connectTo(QString::fromStdString("serial://" + pty_link + "?baud=115200"));
  if (!problem.isEmpty()) {
    QTextStream(stderr) << problem << '\n';
    return 1;
  }
  QElapsedTimer clock;
  clock.start();
  while (link.rates().samples < 20 && clock.elapsed() < 60000)
    pump(app, 50);
  clock.restart();
  while (clock.elapsed() < 25000) {
    const double t = static_cast<double>(clock.elapsed()) * 1e-3;
    session.drive(0.15, 0.5 + 0.35 * std::sin(t * 0.4));
    pump(app, 50);
  }
  session.stopRobot();
  pump(app, 300);

  widgets::PlotsDock& dock = plots.plots();
  while (dock.panelCount() < 3)
    dock.addPanel();
  dock.setWindow_s(30.0);
  const QStringList first{QStringLiteral("MAVLink/LOCAL_POSITION_NED/x"),
                          QStringLiteral("MAVLink/LOCAL_POSITION_NED/y")};
  const QStringList second{QStringLiteral("MAVLink/ATTITUDE/yaw"),
                           QStringLiteral("MAVLink/ATTITUDE/yawspeed")};
  const QStringList third{QStringLiteral("MAVLink/DISTANCE_SENSOR/id 0/current_distance")};
  dock.setCurrentPanel(&dock.panel(0));
  dock.plotFields(first);
  dock.setCurrentPanel(&dock.panel(1));
  dock.plotFields(second);
  dock.setCurrentPanel(&dock.panel(2));
  dock.plotFields(third);
  // The browser on the MAVLink branch: the session's own sources folded, one message open and
  // DISTANCE_SENSOR's instance level showing.
  widgets::FieldBrowser& browser = dock.browser();
  for (int i = 0; i < browser.topLevelItemCount(); ++i)
    browser.topLevelItem(i)->setExpanded(browser.topLevelItem(i)->text(0) == "MAVLink");
  for (const QString& key : {first[0], third[0]}) {
    QTreeWidgetItem* item = browser.itemFor(key);
    if (item != nullptr && key == third[0])
      item = item->parent();  // "id 0": show the instances, not its fields
    for (item = item != nullptr ? item->parent() : nullptr; item != nullptr; item = item->parent())
      item->setExpanded(true);
  }
  if (QTreeWidgetItem* x = browser.itemFor(first[0]))
    browser.setCurrentItem(x);
  browser.scrollToTop();
  window.resizeDocks({&plots.dock()}, {460}, Qt::Vertical);
  window.canvas().zoomToFit();
  dock.refreshNow();
  pump(app, 300);
  const QString path = out + QStringLiteral("/irgs-plots-mavlink.png");
  const bool ok = window.grab().save(path);
  QTextStream(stdout) << (ok ? "wrote " : "FAILED ") << path << '\n';
  return ok ? 0 : 1;
}
