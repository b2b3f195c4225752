#include "app/gui/behaviour_activity.hpp"

#include <algorithm>
#include <stdexcept>
#include <utility>

namespace irgs::gui {

BehaviourActivity::BehaviourActivity(std::shared_ptr<Behaviour> behaviour)
    : behaviour_(std::move(behaviour)) {
  if (!behaviour_)
    throw std::invalid_argument("BehaviourActivity needs a behaviour");
}

void BehaviourActivity::onSample(const TelemetrySample& sample) {
  if (last_sample_s_ >= 0.0 && sample.time_s > last_sample_s_)
    step_s_ = std::clamp(sample.time_s - last_sample_s_, 1e-4, 1.0);
  last_sample_s_ = sample.time_s;
  // The behaviour's clock skips the paused stretches (its watchdogs run on robot time).
  TelemetrySample shifted = sample;
  shifted.time_s -= paused_total_s_;
  command_ = behaviour_->onSample(shifted);
  if (behaviour_->status().finished)
    command_ = {};
}

ActivityCommand BehaviourActivity::command(double time_s) {
  ActivityCommand command;
  command.velocity = command_;
  if (!behaviour_->status().finished)
    command.next_change_s = time_s + step_s_;
  return command;
}

ActivityOutcome BehaviourActivity::outcome() const {
  const BehaviourStatus status = behaviour_->status();
  return {status.finished, status.failed, status.message};
}

void BehaviourActivity::setPaused(bool paused, double time_s) {
  if (paused) {
    paused_at_s_ = time_s;
  } else {
    paused_total_s_ += std::max(0.0, time_s - paused_at_s_);
    command_ = {};
  }
}

}  // namespace irgs::gui
