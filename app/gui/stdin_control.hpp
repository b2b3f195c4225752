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
//   param read | param set NAME VALUE   firmware parameters (linked robot; the Parameters dock):
//                read all / write one (the answer reaches the console)
//   mapbuild start|pause|resume|abort   the Plan tab's map-building buttons (any robot)
//   mapbuild save FILE.yaml             the built map as ROS PGM + YAML (the Save button)
//   screenshot FILE.png                 a PNG of the whole window
//   status       print one status line now    quit        leave (exit status 0)
// Every command is answered with "ok <command>" or "error <command>: <reason>" on stdout.
//
// Status line ("status" then key=value pairs, one line, flushed):
//   wall_s link samples odom_hz sonar_hz sonar_readings_per_s explored_m2 x y theta v w
//   cmd_v cmd_w link_losses reconnects mb mb_progress mb_indices mb_distance_m mb_obstacles
//   loc [loc_steps loc_x loc_y loc_theta loc_dr_x loc_dr_y loc_dr_theta loc_readings
//   loc_accepted loc_caster_periods loc_mean_residual loc_robot_residual]
// link is "none" (simulator) or the link state (connecting, connected, lost) of a MAVLink or
// ARCOS robot; samples and the rates are the robot's telemetry as received. mb is the
// map-building phase with '_' for spaces: "none" when the current or last behaviour is not map
// building, "done", "failed" or "aborted" once it ended (until the next start); mb_indices the
// position indices dropped, mb_distance_m the odometry path driven, mb_obstacles the obstacles
// circumnavigated. loc is the running estimator ("none", or its --localize name) and, when one
// runs, its newest step: samples fed, estimate and dead reckoning (m, rad), its readings and
// accepted counts, the three-caster EKF's J+ periods and mean residual ||e|| (rad) and whether
// the last step used the robot's own reported residual (1) or the re-split one (0).
//
// Console lines: once started, every console message except the periodic sensor lines is also
// printed as "console info|warning|error <text>" (one line), so a test can read what the user
// sees, e.g. the robot's name from the ARCOS handshake.

#include <QElapsedTimer>
#include <QObject>
#include <QPointer>
#include <QString>
#include <optional>

#include "app/gui/session_controller.hpp"

class QSocketNotifier;
class QTimer;

namespace irgs::gui {

class LinkUi;
class PlanningController;

class StdinControl : public QObject {
  Q_OBJECT

 public:
  StdinControl(SessionController& session, LinkUi& link, QObject* parent = nullptr);

  // Starts reading stdin (when `read_commands`) and printing status lines every `interval_s`;
  // console lines are echoed when either is on.
  void start(bool read_commands, std::optional<double> status_interval_s);
  // Runs one command line; returns the answer line (also used by tests).
  QString execute(const QString& line);
  QString statusLine() const;
  // The planning controller for `mapbuild`. Unset, it is the one of the window the link UI
  // belongs to (its parent), found on first use.
  void setPlanning(PlanningController* planning);

 signals:
  void quitRequested();

 private:
  void onReadable();
  void onConsole(EventLevel level, const QString& text);
  void print(const QString& line);
  QString mapBuild(const QStringList& words);
  QString screenshot(const QStringList& words);
  PlanningController* planning() const;

  SessionController& session_;
  LinkUi& link_;
  mutable QPointer<PlanningController> planning_;
  QSocketNotifier* notifier_ = nullptr;
  QTimer* status_timer_ = nullptr;
  bool echo_console_ = false;
  QElapsedTimer wall_;
  QByteArray buffer_;
};

}  // namespace irgs::gui
