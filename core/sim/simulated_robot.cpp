#include "core/sim/simulated_robot.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "core/motion/host_adapters.hpp"

namespace irgs {

SimulatedRobot::SimulatedRobot(WorldMap map, RobotProfile profile, SimConfig config)
    : sim_(std::move(map), std::move(profile), config),
      executor_(
          std::make_unique<motion::MotionExecutor>(motion::motionGeometryOf(sim_.profile()))) {
  last_input_.time_s = sim_.time_s();
  last_input_.odometry = sim_.odometryPose();
}

const RobotProfile& SimulatedRobot::profile() const {
  return sim_.profile();
}

std::string SimulatedRobot::describe() const {
  return "simulator (seed " + std::to_string(sim_.config().seed) + ")";
}

void SimulatedRobot::drive(const VelocityCommand& command) {
  executor_->cancel(last_input_);
  sim_.setCommand(command);
}

void SimulatedRobot::stop() {
  executor_->cancel(last_input_);
  sim_.setCommand({});
}

void SimulatedRobot::start(const motion::Primitive& primitive) {
  executor_->start(primitive, last_input_);
}

void SimulatedRobot::cancel() {
  if (executor_->running())
    sim_.setCommand({});
  executor_->cancel(last_input_);
}

std::vector<motion::MotionReport> SimulatedRobot::takeReports() {
  motion::MotionReport r;
  while (executor_->popReport(r))
    reports_.push_back(r);
  return std::exchange(reports_, {});
}

void SimulatedRobot::setMotionSettings(const motion::MotionSettings& settings) {
  executor_->setSettings(settings);
}

TelemetrySample SimulatedRobot::stepOnce() {
  // A primitive that ends in this step stops the wheels; teleop is left alone otherwise (the
  // idle executor still sees the step: its sonar memory stays current).
  const bool running = executor_->running();
  const VelocityCommand command = executor_->step(last_input_);
  if (running)
    sim_.setCommand(command);
  TelemetrySample sample = sim_.step();
  last_input_ = motion::motionInputOf(sample);
  // Drained every step (the executor's queue is small); kept bounded for a host that never
  // asks.
  motion::MotionReport r;
  while (executor_->popReport(r))
    reports_.push_back(r);
  if (reports_.size() > kMaxKeptReports)
    reports_.erase(reports_.begin(), reports_.begin() + kMaxKeptReports / 2);
  return sample;
}

void SimulatedRobot::runSteps(std::int64_t count, std::vector<TelemetrySample>& out) {
  out.reserve(out.size() + static_cast<std::size_t>(count));
  for (std::int64_t i = 0; i < count; ++i)
    out.push_back(stepOnce());
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
  pending_.push_back(stepOnce());
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
