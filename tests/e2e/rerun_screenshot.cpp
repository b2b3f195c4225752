// Photographs the re-run window for the docs: re-runs RECORDING with the NAME=VALUE parameter
// changes and saves the side-by-side window as OUT.png.
// Usage: rerun_screenshot RECORDING OUT.png [NAME=VALUE ...] (under xvfb-run or offscreen).

#include <QApplication>
#include <QEventLoop>
#include <QMainWindow>
#include <QMenuBar>
#include <QTextStream>
#include <QTimer>
#include <QWidget>
#include <memory>

#include "app/gui/rerun_ui.hpp"
#include "app/gui/resource_locator.hpp"
#include "app/gui/session_controller.hpp"
#include "app/recording/recording_reader.hpp"
#include "core/robot/robot_profile_file.hpp"

using namespace irgs;
using namespace irgs::gui;

int main(int argc, char** argv) {
  QApplication app(argc, argv);
  QTextStream err(stderr);
  if (argc < 3) {
    err << "usage: rerun_screenshot RECORDING OUT.png [NAME=VALUE ...]\n";
    return 2;
  }
  const QString recording_path = QString::fromLocal8Bit(argv[1]);
  const QString out = QString::fromLocal8Bit(argv[2]);
  RobotProfileResult profile =
      loadRobotProfileFile(findResource(QStringLiteral("robots/thesis_robot.json")).toStdString());
  if (!profile.profile) {
    err << "no thesis robot profile\n";
    return 1;
  }
  // The session only lends its profile (a fallback) and its console; no robot is built.
  SessionController session(
      *profile.profile,
      [](const WorldMap&, const RobotProfile&) -> std::unique_ptr<Robot> { return nullptr; });
  QObject::connect(&session, &SessionController::consoleEvent,
                   [&err](EventLevel, double, const QString& text) {
                     err << text << '\n';
                     err.flush();
                   });
  QMainWindow window;
  window.menuBar();
  RerunUi rerun(session, window);

  recording::LoadResult loaded = recording::loadRecording(recording_path.toStdString());
  if (!loaded.recording) {
    err << QString::fromStdString(loaded.error) << '\n';
    return 1;
  }
  recording::RerunParameters changed = recording::recordedRerunParameters(loaded.recording->meta);
  for (int i = 3; i < argc; ++i) {
    if (const auto error = recording::setRerunParameterAssignment(changed, argv[i])) {
      err << QString::fromStdString(*error) << '\n';
      return 2;
    }
  }
  bool ok = false;
  QEventLoop loop;
  QObject::connect(&rerun, &RerunUi::finished, &loop, [&](bool success, const QString&) {
    ok = success;
    loop.quit();
  });
  const QString problem = rerun.start(recording_path, changed);
  if (!problem.isEmpty()) {
    err << problem << '\n';
    return 1;
  }
  loop.exec();
  if (!ok || rerun.compareWindow() == nullptr)
    return 1;
  rerun.compareWindow()->resize(1400, 900);
  QEventLoop settle;
  QTimer::singleShot(500, &settle, &QEventLoop::quit);
  settle.exec();
  app.processEvents();
  return rerun.compareWindow()->grab().save(out) ? 0 : 1;
}
