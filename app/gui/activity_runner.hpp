#pragma once
// The one owner of what drives a session's robot: the session (SessionController) hands every
// sample to the runner and asks it, before every robot update, for the command in force; nobody
// else installs a sample observer or a command schedule. Controllers (behaviours, the drive
// script, navigation, planning, map building, calibration, and host missions) ask the runner
// to start, pause or stop an activity (activity.hpp). One activity runs at a time: a start while
// another runs is refused or preempts it, as the caller asks, and a console line says which
// ("Goal refused: Map building is driving the robot; stop it first" / "Map building preempted
// by Goal"). A new robot ends the activity unless it outlives robots (a drive script).

#include <QObject>
#include <QString>
#include <cstdint>
#include <memory>
#include <optional>

#include "app/gui/activity.hpp"

namespace irgs::gui {

class SessionController;

class ActivityRunner : public QObject {
  Q_OBJECT

 public:
  using Id = std::uint64_t;  // 0: none
  enum class Policy {
    kRefuseIfBusy,  // do not start while another activity runs
    kPreempt,       // stop the running one (it finishes failed, "preempted by ...") and start
  };

  // Created by the session it serves; `session` outlives it.
  explicit ActivityRunner(SessionController& session);
  ~ActivityRunner() override;

  // Starts `activity` under `label` (named in the console). Returns its id, or 0 when it was
  // refused (busy, or it cannot run on this robot: Activity::attach), with a console warning.
  Id start(std::unique_ptr<Activity> activity, const QString& label, Policy policy);
  // Stops the running activity (finished(failed, "<label> aborted: <reason>")) and the robot.
  // No-op when none runs; the second form only when `id` is the one running.
  void stop(const QString& reason);
  void stop(Id id, const QString& reason);
  // Pauses or resumes the running activity (see Activity::setPaused).
  void setPaused(bool paused);

  bool busy() const { return current() != 0; }
  // The running activity's id (0 when none); paused counts as running.
  Id current() const { return active_ && !finishing_ ? id_ : 0; }
  bool paused() const { return busy() && paused_; }
  QString label() const { return busy() ? label_ : QString(); }

  // The session's side, called by SessionController only.
  // Every sample the robot produced, in order, session times.
  void onSample(const TelemetrySample& sample);
  // Drives the robot with the running activity's command for session time `time_s` when it
  // changed (the user may steer in between) and returns the time of the next change.
  double applyCommand(double time_s);
  // The session's robot was replaced.
  void onRobotReplaced();

 signals:
  void started(irgs::gui::ActivityRunner::Id id, const QString& label);
  // After the running activity consumed a sample.
  void sampleConsumed(irgs::gui::ActivityRunner::Id id, const irgs::TelemetrySample& sample);
  // Finished by itself (failed or not) or stopped (failed, the reason in the message).
  void finished(irgs::gui::ActivityRunner::Id id, bool failed, const QString& message);

 private:
  // Announces the end of an activity that finished by itself; its last command is still due.
  void noteIfFinished();
  void retire();

  SessionController& session_;
  std::unique_ptr<Activity> active_;
  Id id_ = 0;
  Id next_id_ = 0;
  QString label_;
  bool paused_ = false;
  bool finishing_ = false;  // finished by itself: one more command() goes out, then retired
  std::optional<VelocityCommand> last_velocity_;  // last one sent: only changes go out
};

}  // namespace irgs::gui
