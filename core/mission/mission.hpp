#pragma once
// A host mission: the ground-station half of an autonomous task (map building, goal travel,
// coverage, landmark delivery). It reads the robot's telemetry — which over a real link is late,
// sparse, or missing for a while — and the reports of the motion primitives it started, and
// answers with requests: start a primitive on the robot, cancel it, or (only for tasks whose
// loop the papers put on the host, and for robots without primitives) a velocity to hold.
// Pure and deterministic: the same samples and reports in the same order give the same
// requests. One MissionRunner (mission_runner.hpp) owns the active mission of a session.

#include <optional>
#include <string_view>
#include <variant>

#include "core/behaviour/behaviour.hpp"
#include "core/motion/primitive.hpp"
#include "core/robot/telemetry.hpp"

namespace irgs {

struct StartPrimitive {
  motion::Primitive primitive;
};
struct CancelPrimitive {};
// A host-closed loop's command (velocity-level behaviours): holds until the next request.
struct HoldVelocity {
  VelocityCommand command;
};
using MissionRequest = std::variant<StartPrimitive, CancelPrimitive, HoldVelocity>;

class Mission {
 public:
  virtual ~Mission() = default;
  // Every sample, oldest first (times on the robot's clock, as Robot::update gives them).
  virtual void onSample(const TelemetrySample& sample) = 0;
  // Every report of the primitives this mission started, in time order with the samples.
  virtual void onReport(const motion::MotionReport& report) = 0;
  // What the robot should do now, if anything changed since the last call.
  virtual std::optional<MissionRequest> takeRequest() = 0;
  virtual BehaviourStatus status() const = 0;
  virtual std::string_view name() const = 0;
  // True when the mission needs primitives (MotionControl); false for host-loop missions.
  virtual bool needsPrimitives() const { return true; }
};

}  // namespace irgs
