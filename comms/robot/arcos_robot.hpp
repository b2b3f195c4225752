#pragma once
// irgs::Robot over ARCOS/P2OS: a Pioneer-class robot (P3-DX/AT, PeopleBot, AmigoBot), MobileSim
// or AMRISim, or `irgs-robot --protocol arcos`, on any transport (serial, TCP; opened from a URL
// with protocol=arcos, e.g. tcp://localhost:8101?protocol=arcos). See docs/pioneer.md.
//
// Threading as LinkedRobot: the transport and the pure ArcosClientSession run on the IoThread;
// samples and console events are queued under a mutex and drained by update()/takeEvents() on
// the caller's thread. drive() sets the translational (VEL, mm/s) and rotational (RVEL, deg/s)
// slots of the session's ArcosCommandScheduler, clamped to the profile's limits: a value goes
// out only when it changed (the newest wins), the scheduler re-sends it or PULSE as the
// keep-alive so the robot's 2 s watchdog only fires when we are gone, and never more than 10
// command packets per second go out, within half the link's byte budget
// (arcos_command_scheduler.hpp; the budget's baud is the URL's `baud`, else the Pioneer's default
// 9600). A caller may call drive() as often as it likes. stop() sends STOP ahead of everything
// else. Each standard SIP becomes one TelemetrySample (arcos_telemetry.hpp) whose time_s is the
// arrival time on this adapter's clock (seconds since open()).
//
// Link loss: no SIP for sip_timeout_s -> kLost; the session re-synchronises on its own and the
// transport is reopened (with backoff) when it fails, e.g. a USB adapter unplugged. The
// commanded velocity is cleared on loss (an event says so) so a robot that comes back does not
// start moving on an old command.

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "comms/arcos/arcos_session.hpp"
#include "comms/link/link_types.hpp"
#include "comms/link/link_url.hpp"
#include "comms/robot/arcos_params.hpp"
#include "comms/transport/io_thread.hpp"
#include "core/robot/motion_control.hpp"
#include "core/robot/robot.hpp"

namespace irgs::comms {

struct ArcosRobotConfig {
  arcos::ArcosSessionConfig session{};
  // Where the robot stands in the map frame when the link first opens (ArcosTelemetryConverter:
  // ARCOS counts from (0, 0, 0) at OPEN). Empty: the robot's own odometry frame.
  std::optional<Pose2> start_pose{};
  double tick_s = 0.02;              // session clock resolution (<= the scheduler's min gap)
  double reconnect_initial_s = 0.5;  // transport reopen backoff after a failure
  double reconnect_max_s = 4.0;
  std::size_t max_pending_samples = 2000;
  std::size_t max_pending_events = 1000;
};

// True when the URL asks for ARCOS (option protocol=arcos).
bool isArcosUrl(const LinkUrl& url);

// The VEL and RVEL arguments for a command: mm/s and deg/s, rounded, clamped to the limits
// (and to the int argument range). Throws std::invalid_argument for a non-finite command.
struct ArcosVelocityArguments {
  int vel_mmps = 0;
  int rvel_degps = 0;
};
ArcosVelocityArguments arcosVelocityArguments(const VelocityCommand& command,
                                              const MotionLimits& limits);

// What the ground station receives, counted since open() and measured on this adapter's clock
// (SIP arrival times) over the last kWindow_s: the ARCOS counterpart of the MAVLink link's
// telemetry rates (a standard SIP is one odometry sample with that cycle's sonar readings).
struct ArcosTelemetryRates {
  static constexpr double kWindow_s = 3.0;
  std::uint64_t samples = 0;         // SIPs converted to TelemetrySamples
  std::uint64_t sonar_readings = 0;  // readings in them (echo or not)
  double sample_hz = 0.0;
  double sonar_hz = 0.0;  // samples carrying at least one sonar reading, per second
  double sonar_readings_per_s = 0.0;
};

class ArcosRobot final : public Robot, public MotionControl {
 public:
  struct OpenResult {
    std::unique_ptr<ArcosRobot> robot;  // null when error is set
    std::string error;
  };
  // Creates the transport and starts connecting; it reconnects on its own from then on.
  static OpenResult open(IoThread& io, const LinkUrl& url, RobotProfile profile,
                         ArcosRobotConfig config = {});
  // The same, keeping `io` alive until the robot is destroyed (for owners that may outlive the
  // code that created the thread, like the GUI session).
  static OpenResult open(std::shared_ptr<IoThread> io, const LinkUrl& url, RobotProfile profile,
                         ArcosRobotConfig config = {});
  ~ArcosRobot() override;
  ArcosRobot(const ArcosRobot&) = delete;
  ArcosRobot& operator=(const ArcosRobot&) = delete;

  // Robot
  const RobotProfile& profile() const override;
  std::string describe() const override;  // "tcp://... (connected: irgs-robot Pioneer p3dx-sh)"
  void drive(const VelocityCommand& command) override;
  void stop() override;
  std::vector<TelemetrySample> update(double wall_elapsed_s) override;
  MotionControl* motionControl() override { return this; }

  // MotionControl: the primitives run on the ground station on each SIP as it arrives and
  // drive the robot's own speed and heading loops (VEL, HEAD, RVEL: arcos_motion.hpp).
  bool supports(motion::PrimitiveKind kind) const override;
  void start(const motion::Primitive& primitive) override;
  void cancel() override;
  std::vector<motion::MotionReport> takeReports() override;

  // For the console, the link-health panel and irgs-sim (same vocabulary as LinkedRobot).
  LinkState linkState() const;
  LinkStats linkStats() const;
  std::vector<LinkEvent> takeEvents();
  arcos::ArcosState sessionState() const;
  std::optional<arcos::RobotIdentity> identity() const;  // from the last SYNC2 reply
  std::uint64_t droppedSamples() const;
  ArcosTelemetryRates telemetryRates() const;
  const ArcosParams& params() const { return params_; }

  struct Impl;

 private:
  ArcosRobot(RobotProfile profile, std::string url_text, ArcosParams params,
             std::shared_ptr<Impl> impl);
  std::shared_ptr<IoThread> io_keepalive_;  // first: destroyed after impl_ has shut down
  RobotProfile profile_;
  std::string url_text_;
  ArcosParams params_;
  std::shared_ptr<Impl> impl_;
};

}  // namespace irgs::comms
