#include "app/gui/activity_runner.hpp"

#include <limits>
#include <utility>

#include "app/gui/session_controller.hpp"

namespace irgs::gui {
namespace {

constexpr double kNoChange_s = std::numeric_limits<double>::infinity();

}  // namespace

ActivityRunner::ActivityRunner(SessionController& session) : session_(session) {}

ActivityRunner::~ActivityRunner() = default;

ActivityRunner::Id ActivityRunner::start(std::unique_ptr<Activity> activity, const QString& label,
                                         Policy policy) {
  if (!activity)
    return 0;
  if (busy() && policy == Policy::kRefuseIfBusy) {
    session_.report(EventLevel::kWarning,
                    tr("%1 refused: %2 is driving the robot; stop it first").arg(label, label_));
    return 0;
  }
  Robot* robot = session_.robot();
  const std::optional<std::string> refusal =
      robot == nullptr ? std::optional<std::string>("there is no robot")
                       : activity->attach({*robot, session_.robotTimeOffset_s()});
  if (refusal) {
    session_.report(EventLevel::kWarning,
                    tr("%1 refused: %2").arg(label, QString::fromStdString(*refusal)));
    return 0;
  }
  if (busy()) {
    session_.report(EventLevel::kInfo, tr("%1 preempted by %2").arg(label_, label));
    stop(tr("preempted by %1").arg(label));
  } else if (active_) {
    retire();  // finished, its last command not sent yet: the new one commands the robot now
  }
  active_ = std::move(activity);
  id_ = ++next_id_;
  label_ = label;
  paused_ = false;
  finishing_ = false;
  last_velocity_.reset();
  const Id id = id_;
  emit started(id, label_);
  const ActivityOutcome outcome = active_->outcome();
  if (id_ == id && outcome.finished) {
    // Nothing to do (an empty plan): it never commanded the robot, so it sends no last command.
    retire();
    emit finished(id, outcome.failed, QString::fromStdString(outcome.message));
  }
  return id;
}

void ActivityRunner::stop(const QString& reason) {
  if (!active_)
    return;
  if (finishing_) {
    retire();  // ended already: its last command is not wanted any more
    return;
  }
  const Id id = id_;
  const QString label = label_;
  active_->abort();
  retire();
  session_.stopRobot();
  emit finished(id, true, tr("%1 aborted: %2").arg(label, reason));
}

void ActivityRunner::stop(Id id, const QString& reason) {
  if (id != 0 && id == current())
    stop(reason);
}

void ActivityRunner::setPaused(bool paused) {
  if (!busy() || paused == paused_)
    return;
  paused_ = paused;
  active_->setPaused(paused, session_.robotTime_s());
  if (paused)
    session_.stopRobot();
  else
    last_velocity_.reset();  // its command goes out again
}

void ActivityRunner::onSample(const TelemetrySample& sample) {
  if (!active_ || paused_ || finishing_)
    return;
  const Id id = id_;
  active_->onSample(sample);
  emit sampleConsumed(id, sample);
  if (id_ == id && active_)  // a receiver may have stopped or replaced it
    noteIfFinished();
}

double ActivityRunner::applyCommand(double time_s) {
  if (!active_ || paused_)
    return kNoChange_s;
  const ActivityCommand command = active_->command(time_s);
  if (!command.velocity) {
    last_velocity_.reset();  // the robot runs on its own; a later velocity goes out again
  } else if (!last_velocity_ || *last_velocity_ != *command.velocity) {
    last_velocity_ = command.velocity;
    session_.drive(command.velocity->linear_mps, command.velocity->angular_radps);
  }
  if (!finishing_) {
    const Id id = id_;
    noteIfFinished();  // e.g. a drive script past its last step
    if (id_ != id || !active_)
      return kNoChange_s;
  }
  if (finishing_) {
    retire();  // that was its last command
    return kNoChange_s;
  }
  return command.next_change_s;
}

void ActivityRunner::onRobotReplaced() {
  if (!active_)
    return;
  if (finishing_) {
    retire();
  } else if (active_->outlivesRobot()) {
    last_velocity_.reset();  // the new robot gets the command in force on its first update
  } else {
    stop(tr("the robot was replaced"));
  }
}

void ActivityRunner::noteIfFinished() {
  const ActivityOutcome outcome = active_->outcome();
  if (!outcome.finished || finishing_)
    return;
  finishing_ = true;
  emit finished(id_, outcome.failed, QString::fromStdString(outcome.message));
}

void ActivityRunner::retire() {
  active_.reset();
  paused_ = false;
  finishing_ = false;
  last_velocity_.reset();
}

}  // namespace irgs::gui
