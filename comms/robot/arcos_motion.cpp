#include "comms/robot/arcos_motion.hpp"

#include <cmath>
#include <utility>

#include "comms/robot/arcos_robot.hpp"
#include "core/motion/host_adapters.hpp"

namespace irgs::comms {

int arcosHeadingArgument(double heading_rad) {
  const int degrees = static_cast<int>(std::lround(radToDeg(wrapAngle(heading_rad))));
  return ((degrees % 360) + 360) % 360;
}

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
  const bool was_running = executor_.running();
  if (!executor_.start(primitive, *last_input_))
    stop_owed_ = stop_owed_ || was_running;  // the running one was cancelled by the refusal
  collect();
}

void ArcosMotion::cancel() {
  if (!last_input_ || !executor_.running())
    return;
  executor_.cancel(*last_input_);
  stop_owed_ = true;
  collect();
}

void ArcosMotion::abort(motion::Reason reason) {
  if (!last_input_ || !executor_.running())
    return;
  executor_.abort(reason, *last_input_);
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
    return ArcosMotionSetpoint{};  // ended on this step: stop the wheels
  }
  const ArcosVelocityArguments arguments = arcosVelocityArguments(command, limits_);
  ArcosMotionSetpoint setpoint;
  setpoint.vel_mmps = arguments.vel_mmps;
  setpoint.rvel_degps = arguments.rvel_degps;
  const std::optional<double>& heading = executor_.headingSetpoint();
  if (heading && std::abs(wrapAngle(*heading - last_input_->odometry.theta)) > kHeadPhase_rad)
    setpoint.head_deg = arcosHeadingArgument(*heading + map_to_arcos_rad);
  return setpoint;
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
