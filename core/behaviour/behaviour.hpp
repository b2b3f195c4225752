#pragma once
// A host-side behaviour: consumes the robot's telemetry one sample at a time and answers with the
// velocity command to hold until the next sample. The same object drives the in-process
// simulator, a linked robot (through the Robot interface) and irgs-sim runs, so a behaviour
// never talks to a robot itself. Pure and deterministic: the same samples give the same commands.

#include <string>
#include <string_view>

#include "core/robot/telemetry.hpp"

namespace irgs {

struct BehaviourStatus {
  std::string phase;      // short, human-readable ("follow wall", "loop closed", "obstacle 2")
  double progress = 0.0;  // 0..1 best estimate, for a progress bar
  bool finished = false;  // done (successfully or not); the command is then zero
  bool failed = false;    // finished without reaching the goal; `message` says why
  std::string message;    // last notable event, for the console
};

class Behaviour {
 public:
  virtual ~Behaviour() = default;
  // Called for every sample, oldest first. The returned command holds until the next call.
  virtual VelocityCommand onSample(const TelemetrySample& sample) = 0;
  virtual BehaviourStatus status() const = 0;
  virtual std::string_view name() const = 0;
};

}  // namespace irgs
