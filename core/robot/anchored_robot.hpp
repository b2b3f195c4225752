#pragma once
// A robot seen in the map frame: its odometry frame is fixed to the map by the first sample it
// sends, which is put at `anchor` (where the robot stands in the map when the run begins).
// Samples and primitive reports come out re-expressed by that rigid transform; primitives go
// in with their headings and waypoints mapped back into the robot's odometry frame. Without an
// anchor it passes everything through. A linked robot counts odometry from wherever it booted
// (ARCOS: from OPEN); host missions and maps work in the map frame.

#include <optional>
#include <string>
#include <vector>

#include "core/robot/robot.hpp"

namespace irgs {

class AnchoredRobot final : public Robot, public MotionControl {
 public:
  // `robot` must outlive this object.
  AnchoredRobot(Robot& robot, std::optional<Pose2> anchor);

  const RobotProfile& profile() const override { return robot_.profile(); }
  std::string describe() const override { return robot_.describe(); }
  void drive(const VelocityCommand& command) override { robot_.drive(command); }
  void stop() override { robot_.stop(); }
  std::vector<TelemetrySample> update(double wall_elapsed_s) override;
  std::vector<TelemetrySample> finish() override;
  SimulationControl* simulationControl() override { return robot_.simulationControl(); }
  MotionControl* motionControl() override;

  // MotionControl (present when the robot's is)
  bool supports(motion::PrimitiveKind kind) const override;
  void start(const motion::Primitive& primitive) override;
  void cancel() override;
  std::vector<motion::MotionReport> takeReports() override;

  // Samples taken from the robot elsewhere, re-expressed (and the first one fixes the frame).
  std::vector<TelemetrySample> toMap(std::vector<TelemetrySample> samples);
  // Map frame <- odometry frame; identity until the first sample (or without an anchor).
  const Pose2& mapFromOdometry() const { return map_from_odometry_; }
  // The robot's odometry pose of the first sample, once seen.
  const std::optional<Pose2>& firstOdometry() const { return first_odometry_; }

 private:
  Robot& robot_;
  std::optional<Pose2> anchor_;
  std::optional<Pose2> first_odometry_;
  Pose2 map_from_odometry_;
};

// The primitive with its headings and waypoints taken from one frame to another by `to_from`
// (a pose of the source frame in the target frame).
motion::Primitive transformed(const motion::Primitive& primitive, const Pose2& to_from);

}  // namespace irgs
