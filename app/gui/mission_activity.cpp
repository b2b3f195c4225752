#include "app/gui/mission_activity.hpp"

#include <algorithm>
#include <stdexcept>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "core/mission/mission_feed.hpp"

namespace irgs::gui {

MissionActivity::MissionActivity(std::shared_ptr<Mission> mission) : mission_(std::move(mission)) {
  if (!mission_)
    throw std::invalid_argument("MissionActivity needs a mission");
}

std::optional<std::string> MissionActivity::attach(const ActivityContext& context) {
  motion_ = context.robot.motionControl();
  robot_time_offset_s_ = context.robot_time_offset_s;
  if (mission_->needsPrimitives() && motion_ == nullptr)
    return std::string(mission_->name()) + " needs a robot that runs motion primitives";
  return std::nullopt;
}

void MissionActivity::onSample(const TelemetrySample& sample) {
  if (last_sample_s_ >= 0.0 && sample.time_s > last_sample_s_)
    step_s_ = std::clamp(sample.time_s - last_sample_s_, 1e-4, 1.0);
  last_sample_s_ = sample.time_s;
  std::vector<motion::MotionReport> reports;
  if (motion_ != nullptr) {
    reports = motion_->takeReports();
    for (motion::MotionReport& report : reports)
      report.time_s += robot_time_offset_s_;
  }
  const auto carryOutRequests = [this] {
    takeRequests(*mission_, [this](const MissionRequest& request) { carryOut(request); });
    return true;
  };
  feedInTimeOrder(
      reports, std::span(&sample, 1),
      [&](const motion::MotionReport& report) {
        mission_->onReport(report);
        return carryOutRequests();
      },
      [&](const TelemetrySample& s) {
        mission_->onSample(s);
        return carryOutRequests();
      });
}

void MissionActivity::carryOut(const MissionRequest& request) {
  std::visit(
      [this](const auto& r) {
        using R = std::decay_t<decltype(r)>;
        if constexpr (std::is_same_v<R, HoldVelocity>) {
          velocity_ = r.command;
        } else {
          velocity_.reset();  // the wheels are the robot's
          if (motion_ == nullptr)
            return;  // a host-loop mission on a robot without primitives: nothing to start
          if constexpr (std::is_same_v<R, StartPrimitive>)
            motion_->start(r.primitive);
          else
            motion_->cancel();
        }
      },
      request);
}

ActivityCommand MissionActivity::command(double time_s) {
  ActivityCommand command;
  if (mission_->status().finished) {
    // Ended: a held velocity stops; a robot running its own primitive is left to it.
    if (velocity_)
      command.velocity = VelocityCommand{};
    return command;
  }
  command.velocity = velocity_;
  command.next_change_s = time_s + step_s_;  // a new request may follow any sample
  return command;
}

ActivityOutcome MissionActivity::outcome() const {
  const BehaviourStatus status = mission_->status();
  return {status.finished, status.failed, status.message};
}

void MissionActivity::abort() {
  if (motion_ != nullptr)
    motion_->cancel();
}

}  // namespace irgs::gui
