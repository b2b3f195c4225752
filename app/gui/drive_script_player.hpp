#pragma once
// Replays a drive script (core/sim/drive_script.hpp) on the session's robot by the robot's
// session time, as an activity of the session's runner: the session splits robot updates at the
// script's change times, so at any finite simulation speed each command starts on the simulator
// step it is due (at speed "max", to within one robot update). The script carries on when the
// robot is replaced (reset), and its last command holds after it ends.

#include <QObject>
#include <QString>
#include <QStringList>
#include <optional>

#include "app/gui/activity.hpp"
#include "app/gui/activity_runner.hpp"
#include "core/sim/drive_script.hpp"

namespace irgs::gui {

class SessionController;

// The script as an activity: its command at session time t is the script's at t - start_s.
class DriveScriptActivity final : public Activity {
 public:
  DriveScriptActivity(DriveScript script, double start_s);

  ActivityCommand command(double time_s) override;
  ActivityOutcome outcome() const override;
  bool outlivesRobot() const override { return true; }

 private:
  DriveScript script_;
  double start_s_ = 0.0;
  bool done_ = false;  // past its last step
};

class DriveScriptPlayer : public QObject {
  Q_OBJECT

 public:
  using Script = irgs::DriveScript;
  struct LoadResult {
    std::optional<Script> script;
    QStringList errors;  // diagnostics, one per line (file:line:col: error: …)
  };
  static LoadResult load(const QString& path);

  DriveScriptPlayer(SessionController& session, Script script, QObject* parent = nullptr);
  ~DriveScriptPlayer() override;

  // Asks the session's runner to start the script at the session's current robot time (script
  // time 0). False when the runner refused it (another activity drives the robot).
  bool start();
  bool finished() const { return finished_; }

 private:
  SessionController& session_;
  Script script_;
  ActivityRunner::Id id_ = 0;
  bool finished_ = false;
};

}  // namespace irgs::gui
