#include "core/mission/mission_runner.hpp"

#include <algorithm>
#include <type_traits>
#include <utility>

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
  waiting_.clear();
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
  if (MotionControl* motion = robot_->motionControl()) {
    std::vector<motion::MotionReport> reports = motion->takeReports();
    waiting_.insert(waiting_.end(), reports.begin(), reports.end());
  }
  std::size_t next = 0;
  for (const TelemetrySample& sample : samples) {
    while (next < waiting_.size() && waiting_[next].time_s <= sample.time_s && running())
      deliver(waiting_[next++]);
    if (!running())
      return;
    deliver(sample);
  }
  // Reports newer than every sample: a robot reports before the telemetry of the same moment
  // arrives, or its telemetry stalls. They go now rather than wait for a sample that may not
  // come (a mission waiting for a final report would wait for ever).
  while (next < waiting_.size() && running())
    deliver(waiting_[next++]);
  waiting_.clear();
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
  while (std::optional<MissionRequest> request = mission_->takeRequest()) {
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
        *request);
  }
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
