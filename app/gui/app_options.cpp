#include "app/gui/app_options.hpp"

#include <QCommandLineParser>
#include <QRegularExpression>
#include <cmath>

#include "comms/link/link_url.hpp"
#include "core/estimation/estimator_runner.hpp"

namespace irgs::gui {
namespace {

// Parses a finite, non-negative number of seconds or a speed factor.
std::optional<double> parseNonNegative(const QString& text) {
  bool ok = false;
  const double value = text.toDouble(&ok);
  if (!ok || !std::isfinite(value) || value < 0.0)
    return std::nullopt;
  return value;
}

std::optional<QSize> parseSize(const QString& text) {
  static const QRegularExpression kPattern(QStringLiteral("^(\\d{2,5})x(\\d{2,5})$"));
  const auto match = kPattern.match(text.trimmed());
  if (!match.hasMatch())
    return std::nullopt;
  const int w = match.captured(1).toInt(), h = match.captured(2).toInt();
  if (w < 320 || h < 240)
    return std::nullopt;
  return QSize(w, h);
}

}  // namespace

AppOptionsResult parseAppOptions(const QStringList& arguments) {
  QCommandLineParser parser;
  parser.setApplicationDescription(
      QStringLiteral("IRGS — Indoor Robot Ground Station: map display, simulator and teleop.\n"
                     "Exit status: 0 ok, 1 a file could not be read or written, 2 bad arguments,\n"
                     "3 --quit-after reached before the requested screenshot."));
  const QCommandLineOption help_option({QStringLiteral("h"), QStringLiteral("help")},
                                       QStringLiteral("Show this help and exit."));
  const QCommandLineOption version_option(QStringLiteral("version"),
                                          QStringLiteral("Show the version and exit."));
  const QCommandLineOption map_option(
      QStringLiteral("map"),
      QStringLiteral("World map to open (IRGS JSON or ROS map YAML). Default: the last map, "
                     "else the bundled default map."),
      QStringLiteral("FILE"));
  const QCommandLineOption robot_option(
      QStringLiteral("robot"),
      QStringLiteral("Robot profile (JSON). Default: the bundled thesis robot."),
      QStringLiteral("FILE"));
  const QCommandLineOption seed_option(QStringLiteral("seed"),
                                       QStringLiteral("Simulator noise seed (default 1)."),
                                       QStringLiteral("N"));
  const QCommandLineOption settings_option(
      QStringLiteral("settings"),
      QStringLiteral("Use this INI file for settings instead of the user's (also "
                     "$IRGS_SETTINGS_FILE)."),
      QStringLiteral("FILE"));
  const QCommandLineOption script_option(
      QStringLiteral("drive-script"),
      QStringLiteral("Replay this drive script as teleop commands, by simulated time."),
      QStringLiteral("FILE"));
  const QCommandLineOption screenshot_option(
      QStringLiteral("screenshot"),
      QStringLiteral("Save a PNG of the whole window and exit (see --screenshot-after)."),
      QStringLiteral("PNG"));
  const QCommandLineOption screenshot_after_option(
      QStringLiteral("screenshot-after"),
      QStringLiteral("Simulated seconds to run before the screenshot (default 5)."),
      QStringLiteral("SIM_SECONDS"));
  const QCommandLineOption quit_after_option(
      QStringLiteral("quit-after"),
      QStringLiteral("Quit after this many wall-clock seconds (exit 3 if a screenshot was "
                     "requested and not yet taken)."),
      QStringLiteral("S"));
  const QCommandLineOption window_size_option(
      QStringLiteral("window-size"),
      QStringLiteral("Initial window size, e.g. 1400x900 (overrides the saved geometry)."),
      QStringLiteral("WxH"));
  const QCommandLineOption speed_option(
      QStringLiteral("speed"),
      QStringLiteral("Initial simulation speed factor: 1, 2, 10 or 0 (= max)."),
      QStringLiteral("FACTOR"));
  const QCommandLineOption connect_option(
      QStringLiteral("connect"),
      QStringLiteral("Start linked to the robot at URL instead of the simulator, e.g. "
                     "serial:///dev/ttyUSB0?baud=115200, serial:///dev/rfcomm0?baud=38400, "
                     "tcp://192.168.4.1:5760, udp://:14550."),
      QStringLiteral("URL"));
  const QCommandLineOption control_option(
      QStringLiteral("control-stdin"),
      QStringLiteral("Read commands from stdin (drive V W, stop, move M, turn DEG, connect URL, "
                     "simulator, status, quit); answers on stdout. For tests and scripts."));
  const QCommandLineOption status_option(
      QStringLiteral("status-interval"),
      QStringLiteral("Print a status line (link state, telemetry rates, pose, explored area) on "
                     "stdout every S seconds."),
      QStringLiteral("S"));
  const QCommandLineOption localize_option(
      QStringLiteral("localize"),
      QStringLiteral("Start localization with this estimator: ekf (stereo-sonar EKF), dr (dead "
                     "reckoning), encoder-gyro, mouse (optical-mouse odometry) or ekf-caster "
                     "(the EKF on the three-caster robot; the Localization menu does the same)."),
      QStringLiteral("ESTIMATOR"));
  const QCommandLineOption record_option(
      QStringLiteral("record"),
      QStringLiteral("Record the session (link frames, events, commands, simulator truth) into "
                     "this new file. Default: a new file under the recordings folder."),
      QStringLiteral("FILE"));
  const QCommandLineOption no_record_option(QStringLiteral("no-record"),
                                            QStringLiteral("Do not record this session."));
  const QCommandLineOption replay_option(
      QStringLiteral("replay"),
      QStringLiteral("Replay this session recording as the robot link (File > Open Recording)."),
      QStringLiteral("FILE"));
  const QCommandLineOption replay_speed_option(
      QStringLiteral("replay-speed"),
      QStringLiteral("Replay speed factor, 0.25 to 16 (default 1)."), QStringLiteral("FACTOR"));
  const QCommandLineOption trajectory_out_option(
      QStringLiteral("trajectory-out"),
      QStringLiteral("At exit, write every pose shown (t, x, y, theta) to this CSV file."),
      QStringLiteral("FILE"));
  const QCommandLineOption grid_out_option(
      QStringLiteral("grid-out"),
      QStringLiteral("At exit, write the occupancy grid's observed cells (log-odds) to this CSV."),
      QStringLiteral("FILE"));
  parser.addOptions({help_option,       version_option,      map_option,
                     robot_option,      seed_option,         settings_option,
                     script_option,     screenshot_option,   screenshot_after_option,
                     quit_after_option, window_size_option,  speed_option,
                     connect_option,    control_option,      status_option,
                     localize_option,   record_option,       no_record_option,
                     replay_option,     replay_speed_option, trajectory_out_option,
                     grid_out_option});

  AppOptionsResult result;
  const auto fail = [&result](const QString& message) {
    result.options.reset();
    result.message = message + QStringLiteral("\nTry 'irgs --help'.");
    result.exit_code = 2;
    return result;
  };
  if (!parser.parse(arguments))
    return fail(parser.errorText());
  if (parser.isSet(help_option)) {
    // Without a QCoreApplication the parser cannot know the program name.
    result.message =
        parser.helpText().replace(QStringLiteral("<executable_name>"), QStringLiteral("irgs"));
    return result;
  }
  if (parser.isSet(version_option)) {
    result.message = QStringLiteral("irgs %1").arg(QStringLiteral(IRGS_VERSION));
    return result;
  }
  if (!parser.positionalArguments().isEmpty())
    return fail(QStringLiteral("unexpected argument '%1' (did you mean --map %1?)")
                    .arg(parser.positionalArguments().first()));

  AppOptions options;
  options.map_file = parser.value(map_option);
  options.robot_file = parser.value(robot_option);
  options.settings_file = parser.value(settings_option);
  options.drive_script_file = parser.value(script_option);
  options.screenshot_file = parser.value(screenshot_option);
  for (const auto* option :
       {&map_option, &robot_option, &settings_option, &script_option, &screenshot_option}) {
    if (parser.isSet(*option) && parser.value(*option).trimmed().isEmpty())
      return fail(QStringLiteral("--%1 needs a file name").arg(option->names().constLast()));
  }
  if (parser.isSet(seed_option)) {
    bool ok = false;
    options.seed = parser.value(seed_option).toULongLong(&ok);
    if (!ok)
      return fail(QStringLiteral("--seed expects a non-negative integer, got '%1'")
                      .arg(parser.value(seed_option)));
  }
  if (parser.isSet(screenshot_after_option)) {
    const auto value = parseNonNegative(parser.value(screenshot_after_option));
    if (!value)
      return fail(QStringLiteral("--screenshot-after expects seconds >= 0, got '%1'")
                      .arg(parser.value(screenshot_after_option)));
    options.screenshot_after_s = *value;
  }
  if (parser.isSet(quit_after_option)) {
    options.quit_after_s = parseNonNegative(parser.value(quit_after_option));
    if (!options.quit_after_s)
      return fail(QStringLiteral("--quit-after expects seconds >= 0, got '%1'")
                      .arg(parser.value(quit_after_option)));
  }
  if (parser.isSet(window_size_option)) {
    options.window_size = parseSize(parser.value(window_size_option));
    if (!options.window_size)
      return fail(QStringLiteral("--window-size expects WIDTHxHEIGHT of at least 320x240, got "
                                 "'%1'")
                      .arg(parser.value(window_size_option)));
  }
  if (parser.isSet(speed_option)) {
    options.sim_speed = parseNonNegative(parser.value(speed_option));
    if (!options.sim_speed || *options.sim_speed > 1000.0)
      return fail(QStringLiteral("--speed expects a factor in [0, 1000] (0 = max), got '%1'")
                      .arg(parser.value(speed_option)));
  }
  if (parser.isSet(connect_option)) {
    options.connect_url = parser.value(connect_option).trimmed();
    const comms::LinkUrlResult url = comms::parseLinkUrl(options.connect_url.toStdString());
    if (!url.url)
      return fail(QStringLiteral("--connect: %1").arg(QString::fromStdString(url.error)));
  }
  options.control_stdin = parser.isSet(control_option);
  if (parser.isSet(localize_option)) {
    options.localize = parser.value(localize_option);
    if (!parseEstimatorKind(options.localize.toStdString()))
      return fail(
          QStringLiteral("--localize expects ekf, dr, encoder-gyro, mouse or ekf-caster, got '%1'")
              .arg(options.localize));
  }
  if (parser.isSet(status_option)) {
    options.status_interval_s = parseNonNegative(parser.value(status_option));
    if (!options.status_interval_s || *options.status_interval_s < 0.01)
      return fail(QStringLiteral("--status-interval expects seconds >= 0.01, got '%1'")
                      .arg(parser.value(status_option)));
  }
  options.record_file = parser.value(record_option);
  options.no_record = parser.isSet(no_record_option);
  options.replay_file = parser.value(replay_option);
  options.trajectory_out_file = parser.value(trajectory_out_option);
  options.grid_out_file = parser.value(grid_out_option);
  for (const auto* option :
       {&record_option, &replay_option, &trajectory_out_option, &grid_out_option}) {
    if (parser.isSet(*option) && parser.value(*option).trimmed().isEmpty())
      return fail(QStringLiteral("--%1 needs a file name").arg(option->names().constLast()));
  }
  if (options.no_record && parser.isSet(record_option))
    return fail(QStringLiteral("--record and --no-record contradict each other"));
  if (!options.replay_file.isEmpty() && !options.connect_url.isEmpty())
    return fail(QStringLiteral("--replay and --connect cannot be used together"));
  if (parser.isSet(replay_speed_option)) {
    options.replay_speed = parseNonNegative(parser.value(replay_speed_option));
    if (!options.replay_speed || *options.replay_speed < 0.25 || *options.replay_speed > 16.0)
      return fail(QStringLiteral("--replay-speed expects a factor in [0.25, 16], got '%1'")
                      .arg(parser.value(replay_speed_option)));
  }
  result.options = options;
  return result;
}

}  // namespace irgs::gui
