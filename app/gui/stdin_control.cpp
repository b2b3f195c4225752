#include "app/gui/stdin_control.hpp"

#include <unistd.h>

#include <QSocketNotifier>
#include <QTimer>
#include <cerrno>
#include <cmath>
#include <cstdio>

#include "app/gui/link_controller.hpp"
#include "app/gui/link_ui.hpp"
#include "app/gui/session_controller.hpp"
#include "core/geometry/types.hpp"
#include "widgets/link/link_health_panel.hpp"

namespace irgs::gui {
namespace {

constexpr int kMaxLineBytes = 4096;  // longer input is garbage, dropped

std::optional<double> number(const QString& text) {
  bool ok = false;
  const double value = text.toDouble(&ok);
  return ok && std::isfinite(value) ? std::optional<double>(value) : std::nullopt;
}

}  // namespace

StdinControl::StdinControl(SessionController& session, LinkUi& link, QObject* parent)
    : QObject(parent), session_(session), link_(link) {
  wall_.start();
}

void StdinControl::start(bool read_commands, std::optional<double> status_interval_s) {
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
  if (command == QStringLiteral("status"))
    return statusLine();
  if (command == QStringLiteral("quit")) {
    emit quitRequested();
    return ok;
  }
  return fail(QStringLiteral("unknown command"));
}

QString StdinControl::statusLine() const {
  const LinkController& link = link_.controller();
  const TelemetryRates rates = link.rates();
  const widgets::LinkHealth health = link.health();
  QString line = QStringLiteral(
                     "status wall_s=%1 link=%2 samples=%3 odom_hz=%4 sonar_hz=%5 "
                     "sonar_readings_per_s=%6 explored_m2=%7")
                     .arg(static_cast<double>(wall_.nsecsElapsed()) * 1e-9, 0, 'f', 3)
                     .arg(link.linked() ? widgets::LinkHealthPanel::stateText(health.state)
                                        : QStringLiteral("none"))
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
              .arg(health.link_losses)
              .arg(health.reconnect_attempts);
  return line;
}

void StdinControl::print(const QString& line) {
  const QByteArray bytes = line.toUtf8() + '\n';
  std::fwrite(bytes.constData(), 1, static_cast<std::size_t>(bytes.size()), stdout);
  std::fflush(stdout);
}

}  // namespace irgs::gui
