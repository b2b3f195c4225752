#pragma once
// The robot side of the motion primitives: one primitive runs at a time, stepped once per
// control period on the robot's own odometry and sonar; its reports queue up for the link (or
// the in-process host) to take. The in-process simulator, `irgs-robot` and a microcontroller
// firmware all run this class, so the primitives behave the same wherever the robot is.
//
// Firmware-grade: fixed-size state (the report queue included), no heap, no exceptions.

#include <array>
#include <cstdint>
#include <variant>

#include "core/motion/drive_primitive.hpp"
#include "core/motion/follow_path_primitive.hpp"
#include "core/motion/follow_wall_primitive.hpp"
#include "core/motion/motion_geometry.hpp"
#include "core/motion/motion_input.hpp"
#include "core/motion/motion_settings.hpp"
#include "core/motion/primitive.hpp"
#include "core/motion/segments_primitive.hpp"
#include "core/motion/sonar_memory.hpp"
#include "core/motion/turn_primitive.hpp"

namespace irgs::motion {

// What runs, for telemetry (the firmware's IRGS_BEHAVIOUR_STATUS) and the console.
struct ExecutorStatus {
  std::uint16_t id = 0;  // 0: nothing has run yet
  PrimitiveKind kind = PrimitiveKind::kTurn;
  bool running = false;
  ReportKind last = ReportKind::kStarted;  // the last report (the final one once stopped)
  Reason reason = Reason::kNone;
  double distance_m = 0.0;  // path driven by this primitive (turns: |angle| turned, rad)
};

class MotionExecutor {
 public:
  static constexpr std::size_t kReportCapacity = 32;

  // `geometry` is copied; settings may be changed later (robot parameters).
  MotionExecutor(const MotionGeometry& geometry, const MotionSettings& settings = {});
  MotionExecutor(const MotionExecutor&) = delete;  // the primitives point into this object
  MotionExecutor& operator=(const MotionExecutor&) = delete;

  // Starts `primitive` at `now` (its time and odometry), replacing the one running (reported
  // kCancelled). Reports kStarted, or kRefused with the reason (an invalid spec, id 0, a kind
  // this robot cannot run: missing sonars). Returns whether it started.
  bool start(const Primitive& primitive, const MotionInput& now);
  // Ends the running primitive (kCancelled); nothing when idle.
  void cancel(const MotionInput& now);
  // Ends the running primitive with kFailed(reason) (a safety stop of the firmware).
  void abort(Reason reason, const MotionInput& now);

  // One control period: the wheel command to hold until the next (zero when idle).
  VelocityCommand step(const MotionInput& input);
  // The heading the last step's command steers toward, when the primitive has one (see
  // StepOutcome::heading_rad): for a robot that holds a heading itself.
  const std::optional<double>& headingSetpoint() const { return heading_setpoint_; }
  // The straight drive the last step was on, when it was one (StepOutcome::distance): for a
  // robot that drives a distance itself.
  const std::optional<StepOutcome::Distance>& distanceSetpoint() const {
    return distance_setpoint_;
  }

  bool running() const { return status_.running; }
  const ExecutorStatus& status() const { return status_; }
  // Reports in the order they were made; false when none is waiting.
  bool popReport(MotionReport& report);
  std::size_t pendingReports() const { return report_count_; }
  std::uint32_t droppedReports() const { return dropped_reports_; }  // queue overflows

  const MotionGeometry& geometry() const { return geometry_; }
  const MotionSettings& settings() const { return settings_; }
  void setSettings(const MotionSettings& settings) { settings_ = settings; }
  // The wall follower of a running FOLLOW_WALL, else null.
  const WallFollowControl* wallFollower() const;

 private:
  void push(ReportKind kind, Reason reason, std::int16_t index, const MotionInput& at);
  void end(ReportKind kind, Reason reason, const MotionInput& at);
  double driven() const;

  MotionGeometry geometry_;
  MotionSettings settings_;
  SonarMemory sonar_;
  std::variant<std::monostate, TurnPrimitive, DrivePrimitive, FollowWallPrimitive,
               SegmentsPrimitive, FollowPathPrimitive>
      active_;
  ExecutorStatus status_;
  std::optional<double> heading_setpoint_;
  std::optional<StepOutcome::Distance> distance_setpoint_;
  std::array<MotionReport, kReportCapacity> reports_{};
  std::size_t report_head_ = 0;
  std::size_t report_count_ = 0;
  std::uint32_t dropped_reports_ = 0;
};

}  // namespace irgs::motion
