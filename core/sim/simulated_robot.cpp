#include "core/sim/simulated_robot.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace irgs {

SimulatedRobot::SimulatedRobot(WorldMap map, RobotProfile profile, SimConfig config)
    : sim_(std::move(map), std::move(profile), config) {}

const RobotProfile& SimulatedRobot::profile() const {
  return sim_.profile();
}

std::string SimulatedRobot::describe() const {
  return "simulator (seed " + std::to_string(sim_.config().seed) + ")";
}

void SimulatedRobot::drive(const VelocityCommand& command) {
  sim_.setCommand(command);
}

void SimulatedRobot::stop() {
  sim_.setCommand({});
}

void SimulatedRobot::runSteps(std::int64_t count, std::vector<TelemetrySample>& out) {
  out.reserve(out.size() + static_cast<std::size_t>(count));
  for (std::int64_t i = 0; i < count; ++i)
    out.push_back(sim_.step());
}

std::vector<TelemetrySample> SimulatedRobot::update(double wall_elapsed_s) {
  std::vector<TelemetrySample> out = std::move(pending_);
  pending_.clear();
  if (paused_)
    return out;
  if (speed_ == 0.0) {
    runSteps(max_steps_, out);
    return out;
  }
  // Negative or NaN elapsed time (a clock going backwards) advances nothing.
  const double wall =
      std::isfinite(wall_elapsed_s) ? std::clamp(wall_elapsed_s, 0.0, kMaxWallStep_s) : 0.0;
  const double owed = carry_steps_ + wall * speed_ / sim_.config().dt_s;
  double whole = std::floor(owed);
  carry_steps_ = owed - whole;
  if (whole > max_steps_) {  // faster than "max" can keep up: run as max, owe nothing
    whole = max_steps_;
    carry_steps_ = 0.0;
  }
  runSteps(static_cast<std::int64_t>(whole), out);
  return out;
}

void SimulatedRobot::setPaused(bool paused) {
  paused_ = paused;
}

bool SimulatedRobot::paused() const {
  return paused_;
}

void SimulatedRobot::setSpeedFactor(double factor) {
  if (!std::isfinite(factor) || factor < 0.0)
    throw std::invalid_argument("SimulatedRobot::setSpeedFactor: factor must be finite and >= 0");
  speed_ = factor;
  carry_steps_ = 0.0;
}

double SimulatedRobot::speedFactor() const {
  return speed_;
}

void SimulatedRobot::singleStep() {
  pending_.push_back(sim_.step());
}

void SimulatedRobot::setMaxStepsPerUpdate(int steps) {
  if (steps < 1)
    throw std::invalid_argument("SimulatedRobot::setMaxStepsPerUpdate: steps must be >= 1");
  max_steps_ = steps;
}

void SimulatedRobot::setMap(WorldMap map) {
  sim_.setMap(std::move(map));
}

}  // namespace irgs
