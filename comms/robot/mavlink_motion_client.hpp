#pragma once
// The ground-station side of the motion primitives over MAVLink (docs/protocol.md section 18),
// pure: no Asio, no threads, no clock (the owner passes `now_s`, its monotonic seconds, and the
// robot's time arrives in the frames). LinkedRobot wires it to a Link (linked_motion.hpp).
//
// Sending: TURN, DRIVE and FOLLOW_WALL go out as COMMAND_LONG through the link's command
// protocol (acknowledged, retried; the result comes back through onCommandResult); SEGMENTS and
// FOLLOW_PATH as IRGS_WAYPOINTS, resent every retry_s until a report or status of its id arrives
// (the robot starts an id once, so a resend that crosses the answer changes nothing). cancel()
// sends MAV_CMD_IRGS_STOP with the newest primitive's id.
//
// Receiving: IRGS_MOTION_REPORTs of the primitives started here become motion::MotionReports
// (time_s = time_boot_ms / 1000, the robot's clock, as TelemetrySample::time_s). A lost report
// frame (bytes lost or corrupted on a Bluetooth link) is made up, so the host never waits for
// ever:
//  * IRGS_BEHAVIOUR_STATUS (2 Hz while a primitive runs, at once on every change) names the
//    primitive, its last report and waypoint: a missing kStarted, turning points and the final
//    report are made from it;
//  * a COMMAND_ACK ACCEPTED without its kStarted makes one; a refusal (DENIED, UNSUPPORTED, ...)
//    without its kRefused makes one with the reason the result implies;
//  * a report or status of a newer primitive ends every older one still open (the robot runs
//    one at a time): kCancelled;
//  * a running primitive unheard for status_timeout_s: MAV_CMD_REQUEST_MESSAGE of the status;
//  * no answer to a start at all (every transmission lost): kRefused (reason kNone);
//  * link loss: kFailed(kSafety) for every open primitive (the robot stops on its own when our
//    heartbeats stop); if the robot turns out to be still running it, it is stopped.
// Made-up reports carry the newest robot time and odometry pose known (onSample). Every
// primitive ends with exactly one final report; kStarted precedes its progress reports, but a
// primitive that ended before the robot confirmed it (replaced, cancelled, link lost) may end
// without one. Reports of primitives started elsewhere (another ground station, the legacy
// behaviour commands, MISSION_START) are not delivered.
//
// takeReports(delivered_until_s, now_s) keeps the order promised by MotionControl: a report
// leaves only once the samples up to its time have been handed out (their newest time is
// `delivered_until_s`), or after report_hold_s when no sample comes (telemetry off or stalled).

#include <cstdint>
#include <deque>
#include <optional>
#include <utility>
#include <vector>

#include "comms/link/link_types.hpp"
#include "comms/mavlink/frame.hpp"
#include "comms/mavlink/messages.hpp"
#include "core/motion/primitive.hpp"

namespace irgs::comms {

struct MotionClientConfig {
  double retry_s = 0.5;  // IRGS_WAYPOINTS resend period (as the command protocol's)
  int max_attempts = 4;  // IRGS_WAYPOINTS transmissions before "no answer"
  // A running primitive of which nothing was heard this long: ask for the status. Longer than
  // the slowest status period (2 s on a 9600-baud link).
  double status_timeout_s = 3.0;
  // A report whose samples have not been handed out after this long leaves anyway.
  double report_hold_s = 0.3;
  std::size_t max_tracked = 16;  // primitives remembered for late frames
};

// A COMMAND_LONG for the command protocol; its result goes back with `primitive_id`.
struct MotionCommand {
  std::uint16_t primitive_id = 0;  // 0: not a start (REQUEST_MESSAGE)
  mavlink::CommandLong command;
};

struct MotionClientOutput {
  std::vector<MotionCommand> commands;
  std::vector<mavlink::IrgsWaypoints> waypoints;
  bool empty() const { return commands.empty() && waypoints.empty(); }
};

class MavlinkMotionClient {
 public:
  // Throws std::invalid_argument for non-positive periods or max_attempts < 1.
  explicit MavlinkMotionClient(MotionClientConfig config = {});

  void setTargetSystem(std::uint8_t system_id) { target_system_ = system_id; }

  // Sends `primitive` (ids are the caller's; reuse one only after its final report). A spec
  // that cannot be encoded is refused here at once (kRefused, kInvalid).
  void start(const motion::Primitive& primitive, double now_s);
  // Stops the newest primitive that is still open (nothing when none is).
  void cancel(double now_s);

  // Frames from the robot (IRGS_MOTION_REPORT, IRGS_BEHAVIOUR_STATUS; others are ignored).
  void onFrame(const mavlink::Frame& frame, double now_s);
  // The command protocol's result of a command from takeOutput().
  void onCommandResult(std::uint16_t primitive_id, const CommandResult& result, double now_s);
  // The newest telemetry sample: robot time and odometry pose, for made-up reports.
  void onSample(double robot_time_s, const Pose2& odometry);
  void onLinkLost(double now_s);
  // Resends and status requests that fell due.
  void tick(double now_s);

  MotionClientOutput takeOutput();
  std::vector<motion::MotionReport> takeReports(double delivered_until_s, double now_s);
  // Reports waiting (whether or not they may leave yet).
  std::size_t pendingReports() const { return reports_.size(); }

 private:
  struct Tracked {
    std::uint16_t id = 0;
    motion::PrimitiveKind kind = motion::PrimitiveKind::kTurn;
    std::uint64_t order = 0;  // start order
    bool heard = false;       // the robot confirmed it: a report, a status or ACCEPTED
    bool started = false;     // kStarted delivered
    bool final = false;
    bool lost_with_link = false;
    std::int16_t last_index = -1;  // last turning point delivered
    std::optional<mavlink::IrgsWaypoints> resend;
    int attempts = 0;
    double next_send_s = 0.0;
    double last_heard_s = 0.0;
    double next_stop_s = 0.0;  // stop of a primitive the robot runs though it ended here
  };
  struct Queued {
    motion::MotionReport report;
    double queued_s = 0.0;
  };

  Tracked* find(std::uint16_t id);
  Tracked& track(const motion::Primitive& primitive, double now_s);
  void onReport(const mavlink::IrgsMotionReport& message, double now_s);
  void onStatus(const mavlink::IrgsBehaviourStatus& status, double now_s);
  void heard(Tracked& t, double now_s);
  // Every open primitive started before `newer` (all open ones for nullptr) ends: kCancelled.
  void endOlder(const Tracked* newer, double robot_time_s, double now_s);
  void deliver(Tracked& t, motion::ReportKind kind, motion::Reason reason, double robot_time_s,
               double now_s, std::int16_t index = -1, double distance_m = 0.0);
  void deliver(Tracked& t, const motion::MotionReport& report, double now_s);
  void ensureStarted(Tracked& t, double robot_time_s, double now_s);
  void stopOnRobot(Tracked& t, double now_s);
  void noteRobotTime(double robot_time_s);

  MotionClientConfig config_;
  std::uint8_t target_system_ = 0;
  std::deque<Tracked> tracked_;
  std::uint64_t next_order_ = 0;
  std::deque<Queued> reports_;
  MotionClientOutput out_;
  double robot_time_s_ = 0.0;  // the newest robot time known
  Pose2 pose_;                 // the newest odometry pose known
  double next_status_request_s_ = 0.0;
};

}  // namespace irgs::comms
