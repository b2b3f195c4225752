#pragma once
// The in-process robot: a Simulator behind the Robot interface, with the ground station owning
// its clock (SimulationControl) and its world (SimulatedWorld).
//
// Time: update(wall_elapsed_s) advances simulated time by wall_elapsed_s * speedFactor(), in
// whole fixed steps; the fraction of a step left over is carried to the next call, so the
// simulated clock tracks wall time without drift. Speed factor 0 means "as fast as possible":
// each update() runs maxStepsPerUpdate() steps (default kDefaultMaxSteps = 1000 steps, 10 s of
// simulated time at dt = 10 ms), whatever the wall time. A wall interval longer than
// kMaxWallStep_s (a stalled host) is not replayed: the simulation pauses for the excess; and no
// update() runs more than maxStepsPerUpdate() steps (a speed factor beyond what the host can
// run behaves as "max", the excess is dropped, not owed). Paused,
// update() runs no steps; singleStep() runs exactly one, its sample returned by the next
// update().
//
// Motion primitives (MotionControl): the robot runs them itself, as irgs-robot's firmware
// does — one MotionExecutor step per simulator step on the previous step's telemetry, its
// command applied to the next step. A host mission that wants to react before the next step
// updates one step at a time. drive() (teleop) cancels a running primitive; stop() too.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/motion/motion_executor.hpp"
#include "core/robot/robot.hpp"
#include "core/sim/simulator.hpp"

namespace irgs {

class SimulatedRobot : public Robot,
                       public SimulationControl,
                       public SimulatedWorld,
                       public MotionControl {
 public:
  static constexpr int kDefaultMaxSteps = 1000;
  static constexpr double kMaxWallStep_s = 1.0;
  static constexpr std::size_t kMaxKeptReports = 4096;  // untaken reports; older ones go

  SimulatedRobot(WorldMap map, RobotProfile profile, SimConfig config = {});

  // Robot
  const RobotProfile& profile() const override;
  std::string describe() const override;
  void drive(const VelocityCommand& command) override;
  void stop() override;
  std::vector<TelemetrySample> update(double wall_elapsed_s) override;
  SimulationControl* simulationControl() override { return this; }
  MotionControl* motionControl() override { return this; }

  // MotionControl
  bool supports(motion::PrimitiveKind) const override { return true; }
  void start(const motion::Primitive& primitive) override;
  void cancel() override;
  std::vector<motion::MotionReport> takeReports() override;
  const motion::MotionExecutor& executor() const { return *executor_; }
  void setMotionSettings(const motion::MotionSettings& settings);
  SimulatedWorld* simulatedWorld() override { return this; }

  // SimulationControl
  void setPaused(bool paused) override;
  bool paused() const override;
  // factor >= 0 (0 = as fast as possible); throws std::invalid_argument otherwise.
  void setSpeedFactor(double factor) override;
  double speedFactor() const override;
  void singleStep() override;

  // SimulatedWorld
  void setWorld(const WorldMap& map) override { setMap(map); }
  void resetPose(const Pose2& pose) override { sim_.resetPose(pose); }
  const std::vector<std::vector<Vec2>>& movingObstaclePolygons() const override {
    return sim_.movingObstaclePolygons();
  }

  // Steps per update() at speed factor 0; throws std::invalid_argument unless >= 1.
  void setMaxStepsPerUpdate(int steps);
  int maxStepsPerUpdate() const { return max_steps_; }

  // The simulator itself, for truth display, teleporting and configuration.
  Simulator& simulator() { return sim_; }
  const Simulator& simulator() const { return sim_; }
  // Replaces the world keeping the robot where it is.
  void setMap(WorldMap map);

 private:
  void runSteps(std::int64_t count, std::vector<TelemetrySample>& out);
  TelemetrySample stepOnce();

  Simulator sim_;
  // On the heap: the executor's primitives point into it, and the robot may be moved.
  std::unique_ptr<motion::MotionExecutor> executor_;
  motion::MotionInput last_input_;  // the newest step's, for the next executor step
  std::vector<motion::MotionReport> reports_;
  bool paused_ = false;
  double speed_ = 1.0;
  int max_steps_ = kDefaultMaxSteps;
  double carry_steps_ = 0.0;              // fraction of a step owed from earlier updates, in [0, 1)
  std::vector<TelemetrySample> pending_;  // produced by singleStep(), not yet returned
};

}  // namespace irgs
