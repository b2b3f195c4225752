#include "app/gui/drive_script_player.hpp"

#include <QFile>
#include <memory>
#include <utility>

#include "app/gui/session_controller.hpp"

namespace irgs::gui {

DriveScriptActivity::DriveScriptActivity(DriveScript script, double start_s)
    : script_(std::move(script)), start_s_(start_s) {}

ActivityCommand DriveScriptActivity::command(double time_s) {
  const double t = time_s - start_s_;
  ActivityCommand command;
  command.velocity = script_.commandAt(t);
  for (const DriveScriptStep& step : script_.steps()) {
    if (step.time_s > t) {
      command.next_change_s = start_s_ + step.time_s;
      return command;
    }
  }
  done_ = true;
  return command;
}

ActivityOutcome DriveScriptActivity::outcome() const {
  return {done_, false, "Drive script finished; its last command holds"};
}

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
    : QObject(parent), session_(session), script_(std::move(script)) {
  connect(&session_.runner(), &ActivityRunner::finished, this,
          [this](ActivityRunner::Id id, bool failed, const QString& message) {
            if (id == 0 || id != id_ || finished_)
              return;
            finished_ = true;
            session_.report(failed ? EventLevel::kWarning : EventLevel::kInfo, message);
          });
}

// The script runs in the runner, on its own copy: it plays on without this object.
DriveScriptPlayer::~DriveScriptPlayer() = default;

bool DriveScriptPlayer::start() {
  if (id_ != 0)
    return true;
  id_ = session_.runner().start(
      std::make_unique<DriveScriptActivity>(script_, session_.robotTime_s()), tr("Drive script"),
      ActivityRunner::Policy::kRefuseIfBusy);
  return id_ != 0;
}

}  // namespace irgs::gui
