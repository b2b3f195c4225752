#include "app/gui/drive_script_player.hpp"

#include <QFile>
#include <limits>

#include "app/gui/session_controller.hpp"

namespace irgs::gui {

DriveScriptPlayer::LoadResult DriveScriptPlayer::load(const QString& path) {
  LoadResult out;
  DriveScriptResult result =
      loadDriveScriptFile(std::filesystem::path(QFile::encodeName(path).toStdString()));
  for (const Diagnostic& d : result.diagnostics) {
    if (d.severity == Severity::kError)
      out.errors << QString::fromStdString(d.toString());
  }
  if (result.script && out.errors.isEmpty())
    out.script = std::move(*result.script);
  else if (out.errors.isEmpty())
    out.errors << path + QStringLiteral(": error: the drive script could not be read");
  return out;
}

DriveScriptPlayer::DriveScriptPlayer(SessionController& session, Script script, QObject* parent)
    : QObject(parent), session_(session), script_(std::move(script)) {}

DriveScriptPlayer::~DriveScriptPlayer() {
  if (started_ && !finished_)
    session_.setCommandSchedule(nullptr);  // the schedule refers to this object
}

void DriveScriptPlayer::start() {
  if (started_)
    return;
  started_ = true;
  start_time_s_ = session_.robotTime_s();
  connect(&session_, &SessionController::commandScheduleFinished, this, [this] {
    if (finished_)
      return;
    finished_ = true;
    session_.report(EventLevel::kInfo, tr("Drive script finished; its last command holds"));
  });
  session_.setCommandSchedule([this](double robot_time_s) {
    const double t = robot_time_s - start_time_s_;
    SessionController::ScheduledCommand scheduled;
    scheduled.command = script_.commandAt(t);
    for (const DriveScriptStep& step : script_.steps()) {
      if (step.time_s > t) {
        scheduled.next_change_s = start_time_s_ + step.time_s;
        break;
      }
    }
    return scheduled;
  });
}

}  // namespace irgs::gui
