#include "core/mission/behaviour_mission.hpp"

#include <cmath>
#include <stdexcept>
#include <utility>

namespace irgs {

BehaviourMission::BehaviourMission(std::unique_ptr<Behaviour> behaviour)
    : owned_(std::move(behaviour)), behaviour_(owned_.get()) {
  if (!behaviour_)
    throw std::invalid_argument("BehaviourMission needs a behaviour");
}

BehaviourMission::BehaviourMission(Behaviour& behaviour) : behaviour_(&behaviour) {}

void BehaviourMission::onSample(const TelemetrySample& sample) {
  command_ = behaviour_->onSample(sample);
  // A behaviour bug must not stop the robot's simulator with an exception.
  if (!std::isfinite(command_.linear_mps) || !std::isfinite(command_.angular_radps))
    command_ = {};
}

std::optional<MissionRequest> BehaviourMission::takeRequest() {
  // Only a change: the robot holds the last velocity (a linked robot repeats it as its
  // protocol's keep-alive).
  if (sent_ && *sent_ == command_)
    return std::nullopt;
  if (!sent_ && command_ == VelocityCommand{})
    return std::nullopt;
  sent_ = command_;
  return HoldVelocity{command_};
}

}  // namespace irgs
