#pragma once
// A host mission (core/mission/mission.hpp) as an activity of the session's runner: one more
// kind of thing that drives the robot, beside behaviours and drive scripts. Every sample goes to
// the mission with the reports of its primitives in time order (the robot's MotionControl,
// reports put on session time; core/mission/mission_feed.hpp), and each request the mission
// makes is carried out: a primitive started or cancelled on the robot, or a velocity held by the
// host (for the host-loop tasks of the papers and for robots without primitives). While a primitive
// runs the host sends no velocity: the wheels are the robot's. Stopped early, the running primitive
// is cancelled.

#include <memory>

#include "app/gui/activity.hpp"
#include "core/mission/mission.hpp"
#include "core/robot/motion_control.hpp"

namespace irgs::gui {

class MissionActivity final : public Activity {
 public:
  // Throws std::invalid_argument for a null mission.
  explicit MissionActivity(std::shared_ptr<Mission> mission);

  // Refused when the mission needs primitives and the robot runs none (no MotionControl).
  std::optional<std::string> attach(const ActivityContext& context) override;
  void onSample(const TelemetrySample& sample) override;
  ActivityCommand command(double time_s) override;
  ActivityOutcome outcome() const override;
  void abort() override;

  const Mission& mission() const { return *mission_; }

 private:
  void carryOut(const MissionRequest& request);

  std::shared_ptr<Mission> mission_;
  MotionControl* motion_ = nullptr;
  double robot_time_offset_s_ = 0.0;
  std::optional<VelocityCommand> velocity_;  // held for the host loop; empty: the robot's own
  double step_s_ = 0.01;                     // robot step, learnt from the sample spacing
  double last_sample_s_ = -1.0;
};

}  // namespace irgs::gui
