#pragma once
// A host-side Behaviour (core/behaviour/behaviour.hpp) as an activity of the session's runner,
// on any robot, simulated or linked: every sample goes to the behaviour, oldest first, and its
// answer holds until one robot step later, so the simulator applies it on the step after the
// sample at every simulation speed. Paused stretches are hidden from the behaviour (its clock
// continues where it stopped, so its watchdogs do not fire). Finished, it stops the robot.

#include <memory>

#include "app/gui/activity.hpp"
#include "core/behaviour/behaviour.hpp"

namespace irgs::gui {

class BehaviourActivity final : public Activity {
 public:
  // Throws std::invalid_argument for a null behaviour.
  explicit BehaviourActivity(std::shared_ptr<Behaviour> behaviour);

  void onSample(const TelemetrySample& sample) override;
  ActivityCommand command(double time_s) override;
  ActivityOutcome outcome() const override;
  void setPaused(bool paused, double time_s) override;

 private:
  std::shared_ptr<Behaviour> behaviour_;
  VelocityCommand command_;
  double step_s_ = 0.01;         // robot step, learnt from the sample spacing
  double last_sample_s_ = -1.0;  // session time of the last sample seen
  double paused_total_s_ = 0.0;  // session time hidden from the behaviour while paused
  double paused_at_s_ = 0.0;
};

}  // namespace irgs::gui
