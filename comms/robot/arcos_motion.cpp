#include "comms/robot/arcos_motion.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "comms/robot/arcos_robot.hpp"
#include "core/motion/host_adapters.hpp"

namespace irgs::comms {

int arcosHeadingArgument(double heading_rad) {
  const int degrees = static_cast<int>(std::lround(radToDeg(wrapAngle(heading_rad))));
  return ((degrees % 360) + 360) % 360;
}

namespace {

constexpr double kSameMoveEnd_m = 0.05;      // two drives ending closer are one
constexpr double kStandingSpeed_mps = 0.01;  // below it the robot is not moving
constexpr long kMaxArgument = 32767;         // an ARCOS int argument

}  // namespace

ArcosMotion::ArcosMotion(const RobotProfile& profile)
    : executor_(motion::motionGeometryOf(profile)), limits_(profile.limits) {}

bool ArcosMotion::supports(motion::PrimitiveKind /*kind*/) const {
  return true;
}

void ArcosMotion::start(const motion::Primitive& primitive) {
  if (!last_input_) {
    // Nothing to start from: no SIP has arrived on this connection yet.
    motion::MotionReport refused;
    refused.id = primitive.id;
    refused.kind = motion::ReportKind::kRefused;
    refused.reason = motion::Reason::kNoAnswer;
    keep(refused);
    return;
  }
  move_.reset();
  const bool was_running = executor_.running();
  if (!executor_.start(primitive, *last_input_))
    stop_owed_ = stop_owed_ || was_running;  // the running one was cancelled by the refusal
  collect();
}

void ArcosMotion::cancel() {
  if (!last_input_ || !executor_.running())
    return;
  executor_.cancel(*last_input_);
  move_.reset();
  stop_owed_ = true;
  collect();
}

void ArcosMotion::abort(motion::Reason reason) {
  if (!last_input_ || !executor_.running())
    return;
  executor_.abort(reason, *last_input_);
  move_.reset();
  stop_owed_ = true;
  collect();
}

std::optional<ArcosMotionSetpoint> ArcosMotion::onSample(const TelemetrySample& sample,
                                                         double map_to_arcos_rad) {
  last_input_ = motion::motionInputOf(sample);
  if (!executor_.running())
    return std::nullopt;
  const VelocityCommand command = executor_.step(*last_input_);
  collect();
  if (!executor_.running()) {
    stop_owed_ = false;
    move_.reset();
    return ArcosMotionSetpoint{};  // ended on this step: stop the wheels
  }
  const ArcosVelocityArguments arguments = arcosVelocityArguments(command, limits_);
  ArcosMotionSetpoint setpoint;
  setpoint.rvel_degps = arguments.rvel_degps;
  if (const auto& distance = executor_.distanceSetpoint()) {
    translate(*distance, setpoint);
  } else {
    move_.reset();
    setpoint.vel_mmps = arguments.vel_mmps;
  }
  const std::optional<double>& heading = executor_.headingSetpoint();
  if (heading && std::abs(wrapAngle(*heading - last_input_->odometry.theta)) > kHeadPhase_rad)
    setpoint.head_deg = arcosHeadingArgument(*heading + map_to_arcos_rad);
  return setpoint;
}

void ArcosMotion::translate(const motion::StepOutcome::Distance& distance,
                            ArcosMotionSetpoint& setpoint) {
  const motion::MotionInput& in = *last_input_;
  const Pose2 aim{in.odometry.x, in.odometry.y,
                  executor_.headingSetpoint().value_or(in.odometry.theta)};
  const Vec2 end = aim.position() + distance.remaining_m * aim.heading();
  const bool same_drive = move_ && (end - move_->end).norm() < kSameMoveEnd_m;
  const bool standing = std::abs(in.measured.linear_mps) < kStandingSpeed_mps;
  setpoint.moving = true;
  if (same_drive && (in.time_s - move_->sent_s < kMoveRetry_s || !standing))
    return;  // the robot is on it
  const ArcosVelocityArguments speed = arcosVelocityArguments({distance.speed_mps, 0.0}, limits_);
  setpoint.move_mm = static_cast<int>(
      std::clamp<long>(std::lround(distance.remaining_m * 1000.0), -kMaxArgument, kMaxArgument));
  setpoint.move_speed_mmps = std::max(1, speed.vel_mmps);
  move_ = MoveSent{end, in.time_s};
}

bool ArcosMotion::takeStopOwed() {
  return std::exchange(stop_owed_, false);
}

std::vector<motion::MotionReport> ArcosMotion::takeReports() {
  collect();
  return std::exchange(reports_, {});
}

void ArcosMotion::collect() {
  motion::MotionReport report;
  while (executor_.popReport(report))
    keep(report);
}

void ArcosMotion::keep(const motion::MotionReport& report) {
  if (reports_.size() >= kMaxKeptReports)
    reports_.erase(reports_.begin());
  reports_.push_back(report);
}

}  // namespace irgs::comms
