#pragma once
// Runs one host mission against a robot: feeds the mission the robot's samples and primitive
// reports (merged in time order, mission_feed.hpp) and applies its requests (start or
// cancel a primitive through the robot's MotionControl, or hold a velocity through drive()).
// The GUI session, irgs-sim and the scenario runner all drive missions through it.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/mission/mission.hpp"
#include "core/robot/robot.hpp"

namespace irgs {

class MissionRunner {
 public:
  // Starts `mission` on `robot` (which must outlive the run or be detached with abort()).
  // Refused, with the reason, when a mission is running (abort it first: preemption is the
  // caller's explicit choice) or when the mission needs primitives the robot does not run.
  std::optional<std::string> start(std::unique_ptr<Mission> mission, Robot& robot);
  // The same for a mission the caller keeps (it must outlive the run).
  std::optional<std::string> start(Mission& mission, Robot& robot);
  // What the robot produced since the last call, as Robot::update returned it; the robot's
  // reports are taken here. Every request the mission makes is applied at once.
  void feed(const std::vector<TelemetrySample>& samples);
  // Stops the robot and ends the mission as failed with `reason`; nothing when none runs.
  void abort(const std::string& reason);

  bool running() const { return mission_ && !finished_; }
  // The current or last mission (kept until the next start), or null.
  Mission* mission() { return mission_; }
  const Mission* mission() const { return mission_; }
  // The mission's status; after abort() failed with the reason.
  BehaviourStatus status() const;
  // Requests applied so far (primitives started, cancels, velocity changes).
  int primitivesStarted() const { return primitives_started_; }

 private:
  void deliver(const motion::MotionReport& report);
  void deliver(const TelemetrySample& sample);
  void applyRequests();
  void finishIfDone();

  std::unique_ptr<Mission> owned_;
  Mission* mission_ = nullptr;
  Robot* robot_ = nullptr;
  bool finished_ = false;
  std::optional<std::string> aborted_;
  int primitives_started_ = 0;
};

}  // namespace irgs
