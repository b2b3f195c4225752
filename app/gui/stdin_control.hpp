#pragma once
// Remote control of a running irgs for end-to-end tests and scripted demos (--control-stdin,
// --status-interval): commands, one per line on stdin, and status lines on stdout.
//
// Commands (SI units except `turn`, which takes degrees like the command panel):
//   drive V W    teleop: V m/s forward, W rad/s counter-clockwise (as the drive pad would)
//   stop         the STOP button
//   move M       firmware behaviour: drive M metres straight (linked robot)
//   turn DEG     firmware behaviour: turn DEG degrees on the spot (linked robot)
//   connect URL  switch to the robot link     simulator   back to the simulator
//   status       print one status line now    quit        leave (exit status 0)
// Every command is answered with "ok <command>" or "error <command>: <reason>" on stdout.
//
// Status line ("status" then key=value pairs, one line, flushed):
//   wall_s link samples odom_hz sonar_hz sonar_readings_per_s explored_m2 x y theta v w
//   cmd_v cmd_w link_losses reconnects
// link is "none" (simulator) or the link state (connecting, connected, lost).

#include <QElapsedTimer>
#include <QObject>
#include <QString>
#include <optional>

class QSocketNotifier;
class QTimer;

namespace irgs::gui {

class LinkUi;
class SessionController;

class StdinControl : public QObject {
  Q_OBJECT

 public:
  StdinControl(SessionController& session, LinkUi& link, QObject* parent = nullptr);

  // Starts reading stdin (when `read_commands`) and printing status lines every `interval_s`.
  void start(bool read_commands, std::optional<double> status_interval_s);
  // Runs one command line; returns the answer line (also used by tests).
  QString execute(const QString& line);
  QString statusLine() const;

 signals:
  void quitRequested();

 private:
  void onReadable();
  void print(const QString& line);

  SessionController& session_;
  LinkUi& link_;
  QSocketNotifier* notifier_ = nullptr;
  QTimer* status_timer_ = nullptr;
  QElapsedTimer wall_;
  QByteArray buffer_;
};

}  // namespace irgs::gui
