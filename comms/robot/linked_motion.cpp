#include "comms/robot/linked_motion.hpp"

#include <utility>

namespace irgs::comms {

LinkedMotion::LinkedMotion(MotionClientConfig config, std::function<double()> clock)
    : clock_(std::move(clock)), client_(config) {}

void LinkedMotion::attach(Link* link) {
  const std::lock_guard lock(mutex_);
  link_ = link;
}

void LinkedMotion::setTargetSystem(std::uint8_t system_id) {
  const std::lock_guard lock(mutex_);
  client_.setTargetSystem(system_id);
}

void LinkedMotion::start(const motion::Primitive& primitive) {
  const std::lock_guard lock(mutex_);
  client_.start(primitive, clock_());
  flushLocked();
}

void LinkedMotion::cancel() {
  const std::lock_guard lock(mutex_);
  client_.cancel(clock_());
  flushLocked();
}

std::vector<motion::MotionReport> LinkedMotion::takeReports() {
  const std::lock_guard lock(mutex_);
  return client_.takeReports(delivered_until_s_, clock_());
}

void LinkedMotion::onFrame(const mavlink::Frame& frame) {
  const std::lock_guard lock(mutex_);
  client_.onFrame(frame, clock_());
  flushLocked();
}

void LinkedMotion::onLinkEvent(const LinkEvent& event) {
  if (event.kind != LinkEventKind::kLinkLost && event.kind != LinkEventKind::kClosed)
    return;
  const std::lock_guard lock(mutex_);
  client_.onLinkLost(clock_());
}

void LinkedMotion::tick() {
  const std::lock_guard lock(mutex_);
  client_.tick(clock_());
  flushLocked();
}

void LinkedMotion::onSample(double robot_time_s, const Pose2& odometry) {
  const std::lock_guard lock(mutex_);
  client_.onSample(robot_time_s, odometry);
}

void LinkedMotion::samplesDelivered(double robot_time_s) {
  const std::lock_guard lock(mutex_);
  delivered_until_s_ = robot_time_s;
}

void LinkedMotion::flushLocked() {
  MotionClientOutput out = client_.takeOutput();
  if (link_ == nullptr || out.empty())
    return;
  for (const mavlink::IrgsWaypoints& m : out.waypoints)
    link_->send(m);
  for (const MotionCommand& c : out.commands) {
    // The result arrives on the io thread, possibly after this object is gone: hold it weakly.
    link_->sendCommand(c.command,
                       [weak = weak_from_this(), id = c.primitive_id](const CommandResult& result) {
                         if (const auto self = weak.lock()) {
                           const std::lock_guard lock(self->mutex_);
                           self->client_.onCommandResult(id, result, self->clock_());
                           self->flushLocked();
                         }
                       });
  }
}

}  // namespace irgs::comms
