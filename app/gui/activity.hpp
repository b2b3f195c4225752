#pragma once
// Something that drives the session's robot for a while: a host behaviour (map building, goal,
// coverage, a delivery, a calibration square), a drive script, a host mission on motion
// primitives. The session's ActivityRunner (activity_runner.hpp) runs one at a time: it hands it
// every sample of the robot and asks it, before every robot update, what the robot should do.
// Qt-free, so a kind of activity is tested on literal samples.

#include <limits>
#include <optional>
#include <string>

#include "core/robot/robot.hpp"
#include "core/robot/telemetry.hpp"

namespace irgs::gui {

// What the activity asks of the robot from now until next_change_s (session time).
struct ActivityCommand {
  // The velocity to hold; empty: leave the wheels to the robot (a motion primitive runs there).
  std::optional<VelocityCommand> velocity;
  // When the answer may change next: the session splits simulator updates there, so a change
  // applies on the step it is due at every simulation speed. Infinity: no further change.
  double next_change_s = std::numeric_limits<double>::infinity();
};

struct ActivityOutcome {
  bool finished = false;  // done by itself (successfully or not)
  bool failed = false;
  std::string message;  // for the console
};

// Where the activity runs: the session's robot and the session time of the robot's time zero
// (robot-clock stamps, e.g. motion reports, plus this are session times).
struct ActivityContext {
  Robot& robot;
  double robot_time_offset_s = 0.0;
};

class Activity {
 public:
  virtual ~Activity() = default;

  // Called once before it starts; a reason when it cannot run on this robot (it is then
  // refused and never runs). Must not command the robot.
  virtual std::optional<std::string> attach(const ActivityContext& context) {
    (void)context;
    return std::nullopt;
  }
  // Every sample of the robot while it runs and is not paused, oldest first, session times.
  virtual void onSample(const TelemetrySample& sample) { (void)sample; }
  // What the robot should do from session time `time_s`; asked before every robot update.
  virtual ActivityCommand command(double time_s) = 0;
  // Once finished, the runner applies command() one last time and ends it.
  virtual ActivityOutcome outcome() const = 0;
  // Paused: no samples, no commands, the robot stopped; the activity may hide the paused
  // stretch from its own clock. `time_s` is the session's robot time at the change.
  virtual void setPaused(bool paused, double time_s) {
    (void)paused;
    (void)time_s;
  }
  // Stopped before its end (the user, or another activity preempting it); the runner stops the
  // robot afterwards. For what runs on the robot itself (a motion primitive) to be cancelled.
  virtual void abort() {}
  // True when it carries on when the session's robot is replaced (a drive script runs by session
  // time); false: a new robot ends it.
  virtual bool outlivesRobot() const { return false; }
};

}  // namespace irgs::gui
