#pragma once
// Replays a drive script (core/sim/drive_script.hpp) as the session's command schedule, by the
// robot's simulated time: the session splits robot updates at the script's change times, so at
// any finite simulation speed each command starts on the simulator step it is due (at speed
// "max", to within one robot update).

#include <QObject>
#include <QString>
#include <QStringList>
#include <optional>

#include "core/sim/drive_script.hpp"

namespace irgs::gui {

class SessionController;

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

  // Starts the script at the session's current robot time (script time 0).
  void start();
  bool finished() const { return finished_; }

 private:
  SessionController& session_;
  Script script_;
  double start_time_s_ = 0.0;
  bool started_ = false;
  bool finished_ = false;
};

}  // namespace irgs::gui
