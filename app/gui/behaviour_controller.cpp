#include "app/gui/behaviour_controller.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "app/gui/session_controller.hpp"

namespace irgs::gui {

BehaviourController::BehaviourController(SessionController& session, QObject* parent)
    : QObject(parent), session_(session) {
  connect(&session_, &SessionController::robotReplaced, this, [this] {
    if (running())
      abort(tr("the robot was replaced"));
  });
}

BehaviourController::~BehaviourController() {
  if (running())
    session_.stopRobot();
  removeHooks();
}

BehaviourStatus BehaviourController::status() const {
  return behaviour_ ? behaviour_->status() : BehaviourStatus{};
}

void BehaviourController::start(std::unique_ptr<Behaviour> behaviour, const QString& label) {
  if (!behaviour)
    return;
  if (running())
    abort(tr("replaced by %1").arg(label));
  behaviour_ = std::move(behaviour);
  label_ = label;
  command_ = {};
  last_sample_s_ = -1.0;
  paused_total_s_ = 0.0;
  paused_ = false;
  finished_ = false;
  last_message_.clear();
  emit started(label_);
  const BehaviourStatus status = behaviour_->status();
  if (status.finished) {  // nothing to do (an empty plan)
    finish(status.failed, QString::fromStdString(status.message));
    return;
  }
  installHooks();
}

void BehaviourController::installHooks() {
  session_.setSampleObserver([this](const TelemetrySample& sample) { onSample(sample); });
  session_.setCommandSchedule([this](double robot_time_s) {
    SessionController::ScheduledCommand scheduled;
    if (!running() || paused_)
      return scheduled;  // zero command, no further change: the session drops the schedule
    scheduled.command = command_;
    scheduled.next_change_s = robot_time_s + step_s_;
    return scheduled;
  });
}

void BehaviourController::removeHooks() {
  session_.setSampleObserver({});
  if (session_.hasCommandSchedule())
    session_.setCommandSchedule({});
}

void BehaviourController::onSample(const TelemetrySample& sample) {
  if (!running() || paused_)
    return;
  if (last_sample_s_ >= 0.0 && sample.time_s > last_sample_s_)
    step_s_ = std::clamp(sample.time_s - last_sample_s_, 1e-4, 1.0);
  last_sample_s_ = sample.time_s;
  // The behaviour's clock skips the paused stretches (its watchdogs run on robot time).
  TelemetrySample shifted = sample;
  shifted.time_s -= paused_total_s_;
  command_ = behaviour_->onSample(shifted);
  const BehaviourStatus status = behaviour_->status();
  emit sampleConsumed(sample);
  if (status.message != last_message_) {
    last_message_ = status.message;
    if (!status.finished && !status.message.empty())
      emit message(QString::fromStdString(status.message));
  }
  emit statusChanged(status);
  if (status.finished) {
    command_ = {};
    finished_ = true;
    // The schedule answers "stop, no further change" on its next query and is dropped then;
    // the observer stays installed (clearing it here would destroy the running function).
    finish(status.failed, QString::fromStdString(status.message));
  }
}

void BehaviourController::abort(const QString& reason) {
  if (!running())
    return;
  finished_ = true;
  command_ = {};
  removeHooks();
  session_.stopRobot();
  finish(true, tr("%1 aborted: %2").arg(label_, reason));
}

void BehaviourController::setPaused(bool paused) {
  if (!running() || paused == paused_)
    return;
  paused_ = paused;
  if (paused_) {
    paused_at_s_ = session_.robotTime_s();
    removeHooks();
    session_.stopRobot();
  } else {
    paused_total_s_ += std::max(0.0, session_.robotTime_s() - paused_at_s_);
    command_ = {};
    installHooks();
  }
}

void BehaviourController::finish(bool failed, const QString& text) {
  finished_ = true;
  emit finished(failed, text);
}

}  // namespace irgs::gui
