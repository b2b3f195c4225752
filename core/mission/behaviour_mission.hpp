#pragma once
// A velocity-level Behaviour (core/behaviour/behaviour.hpp) run as a Mission: the host closes
// its loop, answering every sample with a velocity to hold. For the tasks whose loop the papers
// put on a host computer (paper 002's navigation runs on the robot's onboard PC) and for
// in-process tools; what runs on the robot's own controller is a motion primitive instead.

#include <memory>
#include <optional>

#include "core/behaviour/behaviour.hpp"
#include "core/mission/mission.hpp"

namespace irgs {

class BehaviourMission final : public Mission {
 public:
  explicit BehaviourMission(std::unique_ptr<Behaviour> behaviour);
  // Around a behaviour the caller keeps (it must outlive this mission).
  explicit BehaviourMission(Behaviour& behaviour);

  void onSample(const TelemetrySample& sample) override;
  void onReport(const motion::MotionReport&) override {}
  std::optional<MissionRequest> takeRequest() override;
  BehaviourStatus status() const override { return behaviour_->status(); }
  std::string_view name() const override { return behaviour_->name(); }
  bool needsPrimitives() const override { return false; }

  Behaviour& behaviour() { return *behaviour_; }
  const Behaviour& behaviour() const { return *behaviour_; }

 private:
  std::unique_ptr<Behaviour> owned_;
  Behaviour* behaviour_;
  VelocityCommand command_;
  std::optional<VelocityCommand> sent_;
};

}  // namespace irgs
