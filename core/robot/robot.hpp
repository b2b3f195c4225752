#pragma once
// The one robot interface the ground station drives. Two adapters implement it: the simulated
// robot (in-process, core/sim/simulated_robot.hpp) and the linked robot (over MAVLink, comms/).
// The GUI talks only to this interface and never knows which one it has.

#include <string>
#include <vector>

#include "core/robot/motion_control.hpp"
#include "core/robot/robot_profile.hpp"
#include "core/robot/telemetry.hpp"

namespace irgs {

// Optional extra for robots whose clock the ground station owns (the simulator).
class SimulationControl {
 public:
  virtual ~SimulationControl() = default;
  virtual void setPaused(bool paused) = 0;
  virtual bool paused() const = 0;
  // Speed factor relative to wall time; 0 means "as fast as possible".
  virtual void setSpeedFactor(double factor) = 0;
  virtual double speedFactor() const = 0;
  // Advances exactly one simulator step even when paused.
  virtual void singleStep() = 0;
};

class Robot {
 public:
  virtual ~Robot() = default;

  virtual const RobotProfile& profile() const = 0;
  // Human-readable description of the connection ("simulator", "serial:///dev/rfcomm0 …").
  virtual std::string describe() const = 0;

  // Commands: the robot keeps the last velocity until told otherwise (or its watchdog fires).
  virtual void drive(const VelocityCommand& command) = 0;
  virtual void stop() = 0;

  // Lets the robot do its work for `wall_elapsed_s` of wall time and returns the samples it
  // produced, oldest first. For the simulator this advances simulated time; for a linked robot
  // it drains what arrived.
  virtual std::vector<TelemetrySample> update(double wall_elapsed_s) = 0;

  // Ends the session with this robot: no more data is taken in (a linked robot closes its
  // link), and what the robot still holds is returned, oldest first — a linked robot's last,
  // partly assembled sample — so the session's map ends on the last byte received. The robot
  // may only be destroyed afterwards. A simulator holds nothing.
  virtual std::vector<TelemetrySample> finish() { return {}; }

  // Present only when the ground station owns the robot's clock.
  virtual SimulationControl* simulationControl() { return nullptr; }
  // Present when the robot runs motion primitives itself (motion_control.hpp).
  virtual MotionControl* motionControl() { return nullptr; }
};

}  // namespace irgs
