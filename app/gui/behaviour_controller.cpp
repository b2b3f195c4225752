#include "app/gui/behaviour_controller.hpp"

#include <QScopedValueRollback>
#include <QSignalBlocker>
#include <utility>

#include "app/gui/behaviour_activity.hpp"
#include "app/gui/mission_activity.hpp"
#include "app/gui/session_controller.hpp"

namespace irgs::gui {

BehaviourController::BehaviourController(SessionController& session, QObject* parent)
    : QObject(parent), runner_(session.runner()) {
  connect(&runner_, &ActivityRunner::started, this,
          [this](ActivityRunner::Id id) { onStarted(id); });
  connect(&runner_, &ActivityRunner::sampleConsumed, this, &BehaviourController::onSampleConsumed);
  connect(&runner_, &ActivityRunner::finished, this, &BehaviourController::onFinished);
}

BehaviourController::~BehaviourController() {
  if (!running_)
    return;
  const QSignalBlocker quiet(this);  // the window is going away: nobody is left to tell
  runner_.stop(id_, tr("its controller was closed"));
}

bool BehaviourController::paused() const {
  return running_ && runner_.paused();
}

BehaviourStatus BehaviourController::status() const {
  if (mission_)
    return mission_->status();
  return behaviour_ ? behaviour_->status() : BehaviourStatus{};
}

bool BehaviourController::start(std::shared_ptr<Behaviour> behaviour, const QString& label,
                                ActivityRunner::Policy policy) {
  if (!behaviour)
    return false;
  auto activity = std::make_unique<BehaviourActivity>(behaviour);
  return launch(std::move(activity), std::move(behaviour), nullptr, label, policy);
}

bool BehaviourController::start(std::shared_ptr<Mission> mission, const QString& label,
                                ActivityRunner::Policy policy) {
  if (!mission)
    return false;
  auto activity = std::make_unique<MissionActivity>(mission);
  return launch(std::move(activity), nullptr, std::move(mission), label, policy);
}

bool BehaviourController::launch(std::unique_ptr<Activity> activity,
                                 std::shared_ptr<Behaviour> behaviour,
                                 std::shared_ptr<Mission> mission, const QString& label,
                                 ActivityRunner::Policy policy) {
  // Set before the runner starts it: a behaviour with nothing to do finishes at once, and that
  // must reach this controller's finished() like any other end.
  std::shared_ptr<Behaviour> previous = std::exchange(behaviour_, std::move(behaviour));
  std::shared_ptr<Mission> previous_mission = std::exchange(mission_, std::move(mission));
  const QString previous_label = std::exchange(label_, label);
  const std::string previous_message = std::exchange(last_message_, std::string());
  ActivityRunner::Id id = 0;
  {
    const QScopedValueRollback<bool> starting(starting_, true);
    id = runner_.start(std::move(activity), label, policy);
  }
  if (id == 0) {  // refused: the last one stays the one to look at
    behaviour_ = std::move(previous);
    mission_ = std::move(previous_mission);
    label_ = previous_label;
    last_message_ = previous_message;
    return false;
  }
  return true;
}

void BehaviourController::onStarted(ActivityRunner::Id id) {
  if (!starting_)
    return;  // someone else's
  id_ = id;
  running_ = true;
  emit started(label_);
}

void BehaviourController::abort(const QString& reason) {
  runner_.stop(id_, reason);
}

void BehaviourController::setPaused(bool paused) {
  if (running())
    runner_.setPaused(paused);
}

void BehaviourController::onSampleConsumed(ActivityRunner::Id id, const TelemetrySample& sample) {
  if (id != id_ || (!behaviour_ && !mission_))
    return;
  const BehaviourStatus status = this->status();
  emit sampleConsumed(sample);
  if (status.message != last_message_) {
    last_message_ = status.message;
    if (!status.finished && !status.message.empty())
      emit message(QString::fromStdString(status.message));
  }
  emit statusChanged(status);
}

void BehaviourController::onFinished(ActivityRunner::Id id, bool failed, const QString& message) {
  if (id != id_ || !running_)
    return;
  running_ = false;
  emit finished(failed, message);
}

}  // namespace irgs::gui
