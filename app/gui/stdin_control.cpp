#include "app/gui/stdin_control.hpp"

#include <unistd.h>

#include <QDir>
#include <QFileInfo>
#include <QPixmap>
#include <QSocketNotifier>
#include <QTimer>
#include <QWidget>
#include <cerrno>
#include <cmath>
#include <cstdio>

#include "app/gui/behaviour_controller.hpp"
#include "app/gui/link_controller.hpp"
#include "app/gui/link_format.hpp"
#include "app/gui/link_ui.hpp"
#include "app/gui/localization_controller.hpp"
#include "app/gui/main_window.hpp"
#include "app/gui/parameters_controller.hpp"
#include "app/gui/planning_controller.hpp"
#include "app/gui/session_controller.hpp"
#include "comms/robot/arcos_robot.hpp"
#include "core/geometry/types.hpp"
#include "core/mission/map_building_mission.hpp"
#include "widgets/link/link_health_panel.hpp"

namespace irgs::gui {
namespace {

constexpr int kMaxLineBytes = 4096;  // longer input is garbage, dropped

std::optional<double> number(const QString& text) {
  bool ok = false;
  const double value = text.toDouble(&ok);
  return ok && std::isfinite(value) ? std::optional<double>(value) : std::nullopt;
}

// One status value: no spaces ("follow wall" -> "follow_wall").
QString token(std::string_view text) {
  QString value = QString::fromUtf8(text.data(), static_cast<qsizetype>(text.size()));
  value.replace(QLatin1Char(' '), QLatin1Char('_'));
  return value.isEmpty() ? QStringLiteral("-") : value;
}

// What the status line says about the link, whichever protocol the session's robot speaks.
struct LinkSummary {
  QString state = QStringLiteral("none");
  comms::TelemetryRates rates;
  std::uint32_t link_losses = 0;
  std::uint32_t reconnects = 0;
};

LinkSummary summarise(const LinkController& link) {
  LinkSummary summary;
  if (link.linked()) {  // MAVLink or ARCOS: the controller speaks for both
    const widgets::LinkHealth health = link.health();
    summary.state = widgets::LinkHealthPanel::stateText(health.state);
    summary.rates = link.rates();
    summary.link_losses = health.link_losses;
    summary.reconnects = health.reconnect_attempts;
  }
  return summary;
}

}  // namespace

StdinControl::StdinControl(SessionController& session, LinkUi& link, QObject* parent)
    : QObject(parent), session_(session), link_(link) {
  wall_.start();
}

void StdinControl::start(bool read_commands, std::optional<double> status_interval_s) {
  if ((read_commands || status_interval_s) && !echo_console_) {
    echo_console_ = true;
    connect(&session_, &SessionController::consoleEvent, this,
            [this](EventLevel level, double, const QString& text) { onConsole(level, text); });
  }
  if (read_commands && notifier_ == nullptr) {
    notifier_ = new QSocketNotifier(STDIN_FILENO, QSocketNotifier::Read, this);
    connect(notifier_, &QSocketNotifier::activated, this, &StdinControl::onReadable);
  }
  if (status_interval_s && *status_interval_s > 0.0 && status_timer_ == nullptr) {
    status_timer_ = new QTimer(this);
    status_timer_->setInterval(
        static_cast<int>(std::lround(std::max(*status_interval_s, 0.01) * 1000.0)));
    connect(status_timer_, &QTimer::timeout, this, [this] { print(statusLine()); });
    status_timer_->start();
  }
}

void StdinControl::onReadable() {
  char chunk[1024];
  const ssize_t n = ::read(STDIN_FILENO, chunk, sizeof chunk);
  if (n <= 0) {
    if (n == 0 || errno != EINTR) {
      notifier_->setEnabled(false);  // end of input: keep running, stop listening
    }
    return;
  }
  buffer_.append(chunk, static_cast<qsizetype>(n));
  for (qsizetype end = buffer_.indexOf('\n'); end >= 0; end = buffer_.indexOf('\n')) {
    const QString line = QString::fromUtf8(buffer_.left(end)).trimmed();
    buffer_.remove(0, end + 1);
    if (!line.isEmpty())
      print(execute(line));
  }
  if (buffer_.size() > kMaxLineBytes)
    buffer_.clear();
}

QString StdinControl::execute(const QString& line) {
  const QStringList words = line.simplified().split(QLatin1Char(' '), Qt::SkipEmptyParts);
  if (words.isEmpty())
    return QStringLiteral("error: empty command");
  const QString& command = words.front();
  const auto fail = [&command](const QString& reason) {
    return QStringLiteral("error %1: %2").arg(command, reason);
  };
  const QString ok = QStringLiteral("ok %1").arg(command);
  LinkController& link = link_.controller();
  if (command == QStringLiteral("drive")) {
    const auto v = words.size() == 3 ? number(words[1]) : std::nullopt;
    const auto w = words.size() == 3 ? number(words[2]) : std::nullopt;
    if (!v || !w)
      return fail(QStringLiteral("usage: drive V_MPS W_RADPS"));
    session_.drive(*v, *w);
    return ok;
  }
  if (command == QStringLiteral("stop")) {
    session_.stopRobot();
    return ok;
  }
  if (command == QStringLiteral("move") || command == QStringLiteral("turn")) {
    const auto value = words.size() == 2 ? number(words[1]) : std::nullopt;
    if (!value)
      return fail(QStringLiteral("usage: %1 %2")
                      .arg(command, command == QStringLiteral("move") ? QStringLiteral("METRES")
                                                                      : QStringLiteral("DEGREES")));
    const bool sent = command == QStringLiteral("move") ? link.moveDistance(*value)
                                                        : link.turnAngle(degToRad(*value));
    return sent ? ok : fail(QStringLiteral("no linked robot"));
  }
  if (command == QStringLiteral("param")) {
    auto* params = link_.parent() == nullptr ? nullptr
                                             : link_.parent()->findChild<ParametersController*>(
                                                   QString(), Qt::FindDirectChildrenOnly);
    if (params == nullptr)
      return fail(QStringLiteral("no parameters panel in this window"));
    if (words.size() == 2 && words[1] == QStringLiteral("read"))
      return params->readFirmwareParameters() ? ok : fail(params->statusText());
    const auto value = words.size() == 4 ? number(words[3]) : std::nullopt;
    if (words.size() == 4 && words[1] == QStringLiteral("set") && value) {
      // The command line is the operator's confirmation.
      return params->writeFirmwareParameter(words[2], *value, false) ? ok
                                                                     : fail(params->statusText());
    }
    return fail(QStringLiteral("usage: param read | param set NAME VALUE"));
  }
  if (command == QStringLiteral("connect")) {
    if (words.size() != 2)
      return fail(QStringLiteral("usage: connect URL"));
    const QString problem = link_.connectTo(words[1]);
    return problem.isEmpty() ? ok : fail(problem);
  }
  if (command == QStringLiteral("simulator")) {
    link_.backToSimulator();
    return ok;
  }
  if (command == QStringLiteral("mapbuild"))
    return mapBuild(words);
  if (command == QStringLiteral("screenshot"))
    return screenshot(words);
  if (command == QStringLiteral("status"))
    return statusLine();
  if (command == QStringLiteral("quit")) {
    emit quitRequested();
    return ok;
  }
  return fail(QStringLiteral("unknown command"));
}

QString StdinControl::mapBuild(const QStringList& words) {
  const QString command = QStringLiteral("mapbuild");
  const auto fail = [&command](const QString& reason) {
    return QStringLiteral("error %1: %2").arg(command, reason);
  };
  const QString ok = QStringLiteral("ok %1").arg(command);
  const QString action = words.size() >= 2 ? words[1] : QString();
  const bool save = action == QStringLiteral("save");
  if (words.size() != (save ? 3 : 2) ||
      !(save || action == QStringLiteral("start") || action == QStringLiteral("pause") ||
        action == QStringLiteral("resume") || action == QStringLiteral("abort")))
    return fail(QStringLiteral("usage: mapbuild start|pause|resume|abort|save FILE.yaml"));
  PlanningController* planning = this->planning();
  if (planning == nullptr)
    return fail(QStringLiteral("no planning controller in this window"));
  const bool building = planning->mapBuilding() != nullptr && planning->behaviours().running();
  if (action == QStringLiteral("start")) {
    if (planning->behaviours().running())
      return fail(QStringLiteral("a behaviour is already running (%1)")
                      .arg(planning->behaviours().label()));
    return planning->startMapBuilding() ? ok : fail(QStringLiteral("map building cannot run"));
  }
  if (save) {
    const auto error = planning->saveBuiltMap(words[2]);
    return error ? fail(*error) : ok;
  }
  if (!building)
    return fail(QStringLiteral("map building is not running"));
  if (action == QStringLiteral("abort"))
    planning->stopAll(tr("aborted by the user"));
  else
    planning->setMapBuildingPaused(action == QStringLiteral("pause"));
  return ok;
}

QString StdinControl::screenshot(const QStringList& words) {
  const QString command = QStringLiteral("screenshot");
  if (words.size() != 2)
    return QStringLiteral("error %1: usage: screenshot FILE.png").arg(command);
  auto* window = qobject_cast<QWidget*>(link_.parent());
  if (window == nullptr)
    return QStringLiteral("error %1: no window").arg(command);
  if (auto* main = qobject_cast<MainWindow*>(window))
    main->refreshStatus();  // the status bar is refreshed on a throttle: bring it up to date
  const QString path = words[1];
  if (!QFileInfo(QFileInfo(path).absolutePath()).isDir())
    return QStringLiteral("error %1: no directory for %2").arg(command, path);
  if (!window->window()->grab().save(path, "PNG"))
    return QStringLiteral("error %1: cannot write %2").arg(command, path);
  return QStringLiteral("ok %1").arg(command);
}

void StdinControl::setPlanning(PlanningController* planning) {
  planning_ = planning;
}

PlanningController* StdinControl::planning() const {
  if (planning_.isNull() && link_.parent() != nullptr)
    planning_ =
        link_.parent()->findChild<PlanningController*>(QString(), Qt::FindDirectChildrenOnly);
  return planning_.data();
}

QString StdinControl::statusLine() const {
  const LinkSummary link = summarise(link_.controller());
  const comms::TelemetryRates& rates = link.rates;
  QString line = QStringLiteral(
                     "status wall_s=%1 link=%2 samples=%3 odom_hz=%4 sonar_hz=%5 "
                     "sonar_readings_per_s=%6 explored_m2=%7")
                     .arg(static_cast<double>(wall_.nsecsElapsed()) * 1e-9, 0, 'f', 3)
                     .arg(link.state)
                     .arg(rates.samples)
                     .arg(rates.odometry_hz, 0, 'f', 2)
                     .arg(rates.sonar_hz, 0, 'f', 2)
                     .arg(rates.sonar_readings_per_s, 0, 'f', 1)
                     .arg(session_.grid().exploredArea_m2(), 0, 'f', 3);
  if (const auto& sample = session_.latestSample()) {
    line += QStringLiteral(" x=%1 y=%2 theta=%3 v=%4 w=%5")
                .arg(sample->odometry_pose.x, 0, 'f', 3)
                .arg(sample->odometry_pose.y, 0, 'f', 3)
                .arg(sample->odometry_pose.theta, 0, 'f', 3)
                .arg(sample->measured_velocity.linear_mps, 0, 'f', 3)
                .arg(sample->measured_velocity.angular_radps, 0, 'f', 3);
  }
  line += QStringLiteral(" cmd_v=%1 cmd_w=%2 link_losses=%3 reconnects=%4")
              .arg(session_.command().linear_mps, 0, 'f', 3)
              .arg(session_.command().angular_radps, 0, 'f', 3)
              .arg(link.link_losses)
              .arg(link.reconnects);
  QString phase = QStringLiteral("none");
  double progress = 0.0;
  std::size_t indices = 0;
  double distance_m = 0.0;
  int obstacles = 0;
  if (PlanningController* planning = this->planning()) {
    if (const MapBuildingMission* building = planning->mapBuilding()) {
      phase = token(toString(building->phase()));
      const bool ended = building->phase() == MapBuildingPhase::kDone ||
                         building->phase() == MapBuildingPhase::kFailed;
      if (!planning->behaviours().running() && !ended)
        phase = QStringLiteral("aborted");
      progress = building->status().progress;
      indices = building->allIndices().size();
      distance_m = building->distanceTravelled_m();
      obstacles = building->obstacleCount();
    }
  }
  line += QStringLiteral(" mb=%1 mb_progress=%2 mb_indices=%3 mb_distance_m=%4 mb_obstacles=%5")
              .arg(phase)
              .arg(progress, 0, 'f', 3)
              .arg(indices)
              .arg(distance_m, 0, 'f', 2)
              .arg(obstacles);
  const LocalizationController* loc = link_.parent() != nullptr
                                          ? link_.parent()->findChild<LocalizationController*>(
                                                QString(), Qt::FindDirectChildrenOnly)
                                          : nullptr;
  if (loc == nullptr || loc->runner() == nullptr)
    return line + QStringLiteral(" loc=none");
  const EstimatorRunner& runner = *loc->runner();
  const EstimatorStep& step = runner.lastStep();
  line += QStringLiteral(" loc=%1 loc_steps=%2 loc_x=%3 loc_y=%4 loc_theta=%5 loc_dr_x=%6")
              .arg(QString::fromUtf8(toString(runner.kind())))
              .arg(step.index + 1)
              .arg(step.estimate.x, 0, 'f', 4)
              .arg(step.estimate.y, 0, 'f', 4)
              .arg(step.estimate.theta, 0, 'f', 4)
              .arg(step.dead_reckoning.x, 0, 'f', 4);
  line += QStringLiteral(
              " loc_dr_y=%1 loc_dr_theta=%2 loc_readings=%3 loc_accepted=%4 "
              "loc_caster_periods=%5 loc_mean_residual=%6 loc_robot_residual=%7")
              .arg(step.dead_reckoning.y, 0, 'f', 4)
              .arg(step.dead_reckoning.theta, 0, 'f', 4)
              .arg(runner.metrics().readings)
              .arg(runner.metrics().accepted)
              .arg(runner.metrics().caster_periods)
              .arg(runner.metrics().mean_caster_residual_rad, 0, 'e', 3)
              .arg(step.caster_residual_from_robot ? 1 : 0);
  return line;
}

void StdinControl::onConsole(EventLevel level, const QString& text) {
  QString name;
  switch (level) {
    case EventLevel::kInfo:
      name = QStringLiteral("info");
      break;
    case EventLevel::kWarning:
      name = QStringLiteral("warning");
      break;
    case EventLevel::kError:
      name = QStringLiteral("error");
      break;
    case EventLevel::kSensor:
      return;  // periodic readings: the status line carries the numbers
  }
  print(QStringLiteral("console %1 %2").arg(name, text.simplified()));
}

void StdinControl::print(const QString& line) {
  const QByteArray bytes = line.toUtf8() + '\n';
  std::fwrite(bytes.constData(), 1, static_cast<std::size_t>(bytes.size()), stdout);
  std::fflush(stdout);
}

}  // namespace irgs::gui
