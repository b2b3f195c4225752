#include "core/mission/mission_runner.hpp"

#include <algorithm>
#include <type_traits>
#include <utility>

#include "core/mission/mission_feed.hpp"

namespace irgs {

std::optional<std::string> MissionRunner::start(std::unique_ptr<Mission> mission, Robot& robot) {
  if (!mission)
    return "no mission";
  if (auto refused = start(*mission, robot))
    return refused;
  owned_ = std::move(mission);
  return std::nullopt;
}

std::optional<std::string> MissionRunner::start(Mission& mission, Robot& robot) {
  if (running())
    return "'" + std::string(mission_->name()) + "' is running: stop it first";
  if (mission.needsPrimitives() && robot.motionControl() == nullptr)
    return "this robot does not run motion primitives, which '" + std::string(mission.name()) +
           "' needs";
  owned_.reset();
  mission_ = &mission;
  robot_ = &robot;
  finished_ = false;
  aborted_.reset();
  primitives_started_ = 0;
  if (MotionControl* motion = robot.motionControl())
    motion->takeReports();  // what an earlier primitive left is not this mission's
  applyRequests();
  finishIfDone();
  return std::nullopt;
}

void MissionRunner::feed(const std::vector<TelemetrySample>& samples) {
  if (!running())
    return;
  std::vector<motion::MotionReport> reports;
  if (MotionControl* motion = robot_->motionControl())
    reports = motion->takeReports();
  feedInTimeOrder(
      reports, samples,
      [this](const motion::MotionReport& report) {
        deliver(report);
        return running();
      },
      [this](const TelemetrySample& sample) {
        deliver(sample);
        return running();
      });
}

void MissionRunner::deliver(const motion::MotionReport& report) {
  mission_->onReport(report);
  applyRequests();
  finishIfDone();
}

void MissionRunner::deliver(const TelemetrySample& sample) {
  mission_->onSample(sample);
  applyRequests();
  finishIfDone();
}

void MissionRunner::applyRequests() {
  takeRequests(*mission_, [this](const MissionRequest& request) {
    std::visit(
        [this](const auto& r) {
          using R = std::decay_t<decltype(r)>;
          MotionControl* motion = robot_->motionControl();
          if constexpr (std::is_same_v<R, StartPrimitive>) {
            if (motion) {
              motion->start(r.primitive);
              ++primitives_started_;
            }
          } else if constexpr (std::is_same_v<R, CancelPrimitive>) {
            if (motion)
              motion->cancel();
          } else {
            robot_->drive(r.command);
          }
        },
        request);
  });
}

void MissionRunner::finishIfDone() {
  if (finished_ || !mission_->status().finished)
    return;
  finished_ = true;
  if (MotionControl* motion = robot_->motionControl())
    motion->cancel();
  robot_->stop();
}

void MissionRunner::abort(const std::string& reason) {
  if (!running())
    return;
  finished_ = true;
  aborted_ = reason;
  if (MotionControl* motion = robot_->motionControl())
    motion->cancel();
  robot_->stop();
}

BehaviourStatus MissionRunner::status() const {
  if (!mission_)
    return {};
  BehaviourStatus s = mission_->status();
  if (aborted_) {
    s.finished = true;
    s.failed = true;
    s.message = *aborted_;
  }
  return s;
}

}  // namespace irgs
