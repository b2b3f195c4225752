// irgs: the Indoor Robot Ground Station GUI.
//
//   irgs [--map FILE] [--robot FILE] [--seed N] [--settings FILE] [--drive-script FILE]
//        [--screenshot PNG] [--screenshot-after SIM_SECONDS] [--quit-after S]
//        [--window-size WxH] [--speed FACTOR] [--connect URL] [--control-stdin]
//        [--status-interval S] [--record FILE | --no-record] [--replay FILE]
//        [--replay-speed X] [--trajectory-out CSV] [--grid-out CSV]
//
// Exit codes: 0 normal; 1 a file could not be read or written; 2 bad arguments;
// 3 --quit-after reached before the requested screenshot.

#include <QApplication>
#include <QDir>
#include <QFileInfo>
#include <QTextStream>
#include <csignal>
#include <exception>
#include <memory>

#include "app/gui/app_options.hpp"
#include "app/gui/app_settings.hpp"
#include "app/gui/automation.hpp"
#include "app/gui/calibration_controller.hpp"
#include "app/gui/drive_input_controller.hpp"
#include "app/gui/drive_script_player.hpp"
#include "app/gui/event_format.hpp"
#include "app/gui/link_ui.hpp"
#include "app/gui/localization_controller.hpp"
#include "app/gui/main_window.hpp"
#include "app/gui/map_file_actions.hpp"
#include "app/gui/recording_ui.hpp"
#include "app/gui/rerun_ui.hpp"
#include "app/gui/session_controller.hpp"
#include "app/gui/startup.hpp"
#include "app/gui/stdin_control.hpp"
#include "core/sim/gyro_sim.hpp"
#include "core/sim/sim_presets.hpp"
#include "core/sim/simulated_robot.hpp"

namespace {

using namespace irgs::gui;

constexpr int kExitFileError = 1;
constexpr int kExitUsage = 2;
const QSize kDefaultWindowSize(1400, 880);
constexpr int kMaxSpeedStepsPerUpdate = 20;

QTextStream& err() {
  static QTextStream stream(stderr);
  return stream;
}

void printLines(const QStringList& lines) {
  for (const QString& line : lines)
    err() << "irgs: " << line << '\n';
  err().flush();
}

// Help, version and bad arguments need no display: answer them before QApplication connects to
// one. When Qt's own arguments are present, parse again after QApplication has removed them.
// Today's robot: the in-process simulator, rebuilt (same seed) for every map and reset.
RobotFactory simulatedRobotFactory(std::uint64_t seed) {
  return [seed](const irgs::WorldMap& world,
                const irgs::RobotProfile& profile) -> std::unique_ptr<irgs::Robot> {
    // The same typical odometry errors as irgs-sim: a real robot's map smears, so does ours.
    irgs::SimConfig config = irgs::typicalSimConfig();
    // And a yaw-rate gyro at the AUTOGYRO level of paper 001 (its own random stream: every
    // other output is the same as without it), so the encoder + gyro filter has its sensor.
    config.gyro = irgs::autogyroErrorModel();
    config.seed = seed;
    auto robot = std::make_unique<irgs::SimulatedRobot>(world, profile, config);
    // At speed "max" the session calls update() repeatedly within its tick budget; small
    // updates keep scripted commands and key presses within 0.2 s of simulated time.
    robot->setMaxStepsPerUpdate(kMaxSpeedStepsPerUpdate);
    return robot;
  };
}

std::optional<int> answerWithoutDisplay(int argc, char** argv) {
  QStringList arguments;
  for (int i = 0; i < argc; ++i)
    arguments << QString::fromLocal8Bit(argv[i]);
  const AppOptionsResult parsed = parseAppOptions(arguments);
  if (parsed.options)
    return std::nullopt;
  if (parsed.exit_code == 0) {
    QTextStream(stdout) << parsed.message << '\n';
    return 0;
  }
  // Qt's own options (-platform, -style, …) are single-dash words; without any, the error is
  // ours to report, display or not.
  for (const QString& argument : arguments.mid(1)) {
    if (argument.size() > 2 && argument.startsWith(QLatin1Char('-')) && argument[1] != '-')
      return std::nullopt;
  }
  QTextStream(stderr) << "irgs: " << parsed.message << '\n';
  return parsed.exit_code;
}

}  // namespace

int main(int argc, char** argv) {
  if (const auto code = answerWithoutDisplay(argc, argv))
    return *code;

  QApplication app(argc, argv);
  QApplication::setOrganizationName(QString::fromLatin1(kOrganisation));
  QApplication::setApplicationName(QString::fromLatin1(kApplication));
  QApplication::setApplicationDisplayName(QStringLiteral("IRGS"));
  QApplication::setApplicationVersion(QStringLiteral(IRGS_VERSION));

  const AppOptionsResult parsed = parseAppOptions(QApplication::arguments());
  if (!parsed.options) {
    QTextStream out(parsed.exit_code == 0 ? stdout : stderr);
    out << (parsed.exit_code == 0 ? QString() : QStringLiteral("irgs: ")) << parsed.message << '\n';
    return parsed.exit_code;
  }
  const AppOptions& options = *parsed.options;
  if (!options.screenshot_file.isEmpty() &&
      !QFileInfo(QFileInfo(options.screenshot_file).absolutePath()).isDir()) {
    err() << "irgs: error: --screenshot: directory of " << options.screenshot_file
          << " does not exist\n";
    return kExitUsage;
  }

  std::unique_ptr<QSettings> settings = openSettings(options.settings_file);

  Loaded<irgs::RobotProfile> robot = loadStartupRobot(options.robot_file);
  printLines(robot.warnings);
  if (!robot.value) {
    printLines(robot.errors);
    err() << "irgs: error: cannot use robot profile "
          << (robot.file.isEmpty() ? options.robot_file : robot.file) << '\n';
    return kExitFileError;
  }

  // The map: --map, else the last map used (if it still loads), else the bundled default.
  QStringList startup_notes;
  QString map_request = options.map_file;
  if (map_request.isEmpty()) {
    const QString last = settings->value(QString::fromLatin1(settings_key::kLastMap)).toString();
    if (!last.isEmpty() && QFileInfo(last).isFile())
      map_request = last;
  }
  Loaded<irgs::WorldMap> map = loadStartupMap(map_request);
  if (!map.value && options.map_file.isEmpty() && !map_request.isEmpty()) {
    startup_notes << QStringLiteral("The last map %1 no longer loads; opened the default map.")
                         .arg(map_request);
    map = loadStartupMap(QString());
  }
  printLines(map.warnings);
  if (!map.value) {
    printLines(map.errors);
    err() << "irgs: error: cannot open map " << (map.file.isEmpty() ? map_request : map.file)
          << '\n';
    return kExitFileError;
  }

  std::optional<DriveScriptPlayer::Script> script;
  if (!options.drive_script_file.isEmpty()) {
    auto loaded = DriveScriptPlayer::load(options.drive_script_file);
    if (!loaded.script) {
      printLines(loaded.errors);
      err() << "irgs: error: cannot use drive script " << options.drive_script_file << '\n';
      return kExitFileError;
    }
    script = std::move(loaded.script);
  }

  std::unique_ptr<SessionController> session_owner;
  try {
    session_owner =
        std::make_unique<SessionController>(*robot.value, simulatedRobotFactory(options.seed));
  } catch (const std::exception& e) {  // a profile the mapper cannot use
    err() << "irgs: error: robot profile " << robot.file << " cannot be used: " << e.what() << '\n';
    return kExitFileError;
  }
  SessionController& session = *session_owner;
  MainWindow window(session, *settings);
  session.report(EventLevel::kInfo, QStringLiteral("Robot '%1' (%2)")
                                        .arg(QString::fromStdString(robot.value->name),
                                             QFileInfo(robot.file).fileName()));
  if (!robot.value->sonars.empty())
    session.report(EventLevel::kInfo, formatSonarLegend(*robot.value));
  for (const QString& line : robot.warnings)
    session.report(EventLevel::kWarning, line);
  for (const QString& line : map.warnings)
    session.report(EventLevel::kWarning, line);
  for (const QString& line : startup_notes)
    session.report(EventLevel::kWarning, line);
  try {
    session.loadWorld(std::move(*map.value), map.file);
  } catch (const std::exception& e) {  // a map the simulator cannot use
    err() << "irgs: error: map " << map.file << " cannot be simulated: " << e.what() << '\n';
    return kExitFileError;
  }
  window.mapFiles().setCurrentFile(map.file);
  if (options.sim_speed)
    session.setSpeedFactor(*options.sim_speed);

  // Session recording (app/recording) before any link opens, so it sees every byte; a replay
  // is not recorded again.
  auto* recording = new RecordingUi(session, window.linkUi().controller(), window);
  new RerunUi(session, window, recording->openRecordingAction());   // File > Re-run with ...
  new CalibrationController(window, session, robot.file, &window);  // the Calibrate menu
  new DriveInputController(window.commandPanel(), session, makeSdlGamepadSource(), &window);
  recording->setCollectTrajectory(!options.trajectory_out_file.isEmpty());
  recording->setRobotFile(robot.file);
  if (options.replay_file.isEmpty() && !options.no_record) {
    const QString path = options.record_file.isEmpty()
                             ? RecordingUi::newRecordingPath(
                                   RecordingUi::defaultRecordingsDir(options.settings_file))
                             : options.record_file;
    const QString problem = recording->startRecording(path);
    if (!problem.isEmpty()) {
      if (!options.record_file.isEmpty()) {
        err() << "irgs: error: --record " << path << ": " << problem << '\n';
        return kExitFileError;
      }
      session.report(EventLevel::kWarning, QStringLiteral("Not recording: %1").arg(problem));
    }
  }
  if (!options.replay_file.isEmpty()) {
    const QString problem =
        recording->openReplay(options.replay_file, options.replay_speed.value_or(1.0));
    if (!problem.isEmpty()) {
      err() << "irgs: error: --replay " << options.replay_file << ": " << problem << '\n';
      return kExitFileError;
    }
  }

  if (!options.connect_url.isEmpty()) {
    const QString problem = window.linkUi().connectTo(options.connect_url);
    if (!problem.isEmpty()) {
      err() << "irgs: error: --connect " << options.connect_url << ": " << problem << '\n';
      return kExitUsage;
    }
  }

  window.restoreSettings(kDefaultWindowSize);
  if (options.window_size)
    window.resize(*options.window_size);
  if (!options.localize.isEmpty())
    window.localization().setEstimator(irgs::parseEstimatorKind(options.localize.toStdString()));

  std::unique_ptr<DriveScriptPlayer> player;
  if (script) {
    player = std::make_unique<DriveScriptPlayer>(session, std::move(*script));
    session.report(EventLevel::kInfo, QStringLiteral("Replaying drive script %1")
                                          .arg(QFileInfo(options.drive_script_file).fileName()));
  }

  Automation::Plan plan;
  plan.screenshot_file = options.screenshot_file;
  plan.screenshot_after_s = options.screenshot_after_s;
  plan.quit_after_s = options.quit_after_s;
  plan.before_grab = [&window] { window.refreshStatus(); };
  Automation automation(session, window, std::move(plan));
  // Automated runs leave the user's window layout alone: no saveSettings() here.
  QObject::connect(&automation, &Automation::finished, &app,
                   [](int code) { QApplication::exit(code); });

  StdinControl control(session, window.linkUi());
  QObject::connect(&control, &StdinControl::quitRequested, &app, [] { QApplication::exit(0); });
  if (options.control_stdin || options.status_interval_s)
    std::signal(SIGPIPE, SIG_IGN);  // a reader that went away must not kill the GUI
  control.start(options.control_stdin, options.status_interval_s);

  window.show();
  session.start();
  if (player)
    player->start();
  automation.start();
  const int code = QApplication::exec();
  // End the robot's session first (a linked robot closes its link and hands over the sample it
  // held), then close the recording: the recording ends on the last byte the map took in, so a
  // replay of it builds the same map.
  session.finishRobot();
  recording->stopRecording();
  std::string dump_error;
  if (!options.trajectory_out_file.isEmpty())
    dump_error = irgs::recording::writeTrajectoryCsv(recording->trajectory(),
                                                     options.trajectory_out_file.toStdString());
  if (dump_error.empty() && !options.grid_out_file.isEmpty())
    dump_error = irgs::recording::writeGridCsv(session.grid(), options.grid_out_file.toStdString());
  if (!dump_error.empty()) {
    err() << "irgs: error: " << QString::fromStdString(dump_error) << '\n';
    return code == 0 ? kExitFileError : code;
  }
  return code;
}
