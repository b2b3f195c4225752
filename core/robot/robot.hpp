#pragma once
// The one robot interface the ground station drives. Two kinds implement it: the simulated
// robot (in-process, core/sim/simulated_robot.hpp) and the robots at the far end of a link
// (comms::RemoteRobot: MAVLink or ARCOS). The GUI talks only to this interface and never knows
// which one it has: what differs is offered as optional capabilities (null where absent), never
// found out by a cast (docs/decisions/robot-capabilities.md; ctest -R Layering checks it).

#include <string>
#include <vector>

#include "core/robot/motion_control.hpp"
#include "core/robot/robot_profile.hpp"
#include "core/robot/telemetry.hpp"

namespace irgs {

struct WorldMap;
namespace comms {
// A robot behind a link and its link's vocabulary (comms/robot/remote_robot.hpp). Named here
// only as an incomplete type: core never uses it; the app layer, which links comms, does.
class RemoteRobot;
}  // namespace comms

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

// Optional extra for robots that live in a world the ground station simulates: the world can be
// swapped under the robot and the robot put somewhere by hand. The true pose needs no accessor:
// such a robot's samples carry it (TelemetrySample::true_pose).
class SimulatedWorld {
 public:
  virtual ~SimulatedWorld() = default;
  // Replaces the world (the map editor's edits), the robot staying where it is.
  virtual void setWorld(const WorldMap& map) = 0;
  // Teleports the robot to `pose` (map frame); odometry restarts there and the robot stops.
  // Throws std::invalid_argument for a non-finite pose.
  virtual void resetPose(const Pose2& pose) = 0;
  // Outlines (map frame) of the world's moving obstacles now, in map order.
  virtual const std::vector<std::vector<Vec2>>& movingObstaclePolygons() const = 0;
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
  // Present only when the ground station simulates the robot's world.
  virtual SimulatedWorld* simulatedWorld() { return nullptr; }
  // Present when the robot is at the far end of a link (MAVLink, ARCOS): link state, statistics,
  // console events, telemetry rates, a confirmed stop and the link's optional capabilities.
  virtual comms::RemoteRobot* remoteRobot() { return nullptr; }
  // Present when the robot runs motion primitives itself (motion_control.hpp).
  virtual MotionControl* motionControl() { return nullptr; }
};

}  // namespace irgs
