#pragma once
// LinkedRobot's MotionControl: the pure MavlinkMotionClient behind a mutex, wired to the Link.
// The robot's owner thread calls start/cancel/takeReports; LinkedRobot's io-thread callbacks
// feed it frames, link events, the timer and the samples it releases. Commands go through the
// link's command protocol (their results come back on the io thread), IRGS_WAYPOINTS as plain
// frames. Lock order: LinkedRobot's state mutex, then this one (never the other way).

#include <functional>
#include <memory>
#include <mutex>
#include <vector>

#include "comms/link/link.hpp"
#include "comms/robot/mavlink_motion_client.hpp"
#include "core/robot/motion_control.hpp"

namespace irgs::comms {

class LinkedMotion final : public MotionControl, public std::enable_shared_from_this<LinkedMotion> {
 public:
  // `clock`: the owner's monotonic seconds (retries, timeouts, the report hold).
  LinkedMotion(MotionClientConfig config, std::function<double()> clock);

  // The link to send on; null detaches (nothing is sent from then on).
  void attach(Link* link);
  void setTargetSystem(std::uint8_t system_id);

  // MotionControl: every kind runs on the firmware.
  bool supports(motion::PrimitiveKind) const override { return true; }
  void start(const motion::Primitive& primitive) override;
  void cancel() override;
  std::vector<motion::MotionReport> takeReports() override;

  // From LinkedRobot (io thread unless said otherwise).
  void onFrame(const mavlink::Frame& frame);
  void onLinkEvent(const LinkEvent& event);
  void tick();
  void onSample(double robot_time_s, const Pose2& odometry);
  // Samples up to this robot time were handed out by Robot::update() (owner thread).
  void samplesDelivered(double robot_time_s);

 private:
  void flushLocked();

  std::function<double()> clock_;
  std::mutex mutex_;
  MavlinkMotionClient client_;
  Link* link_ = nullptr;
  double delivered_until_s_ = -1.0;
};

}  // namespace irgs::comms
