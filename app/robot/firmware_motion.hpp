#pragma once
// The motion primitives of the virtual firmware: every behaviour (MOVE_DISTANCE, TURN_ANGLE,
// FOLLOW_WALL, IRGS_WAYPOINTS and MISSION_START) runs through ONE motion::MotionExecutor, the
// firmware-grade code a microcontroller would run (core/motion). This class turns dialect
// messages into primitives, keeps the state IRGS_BEHAVIOUR_STATUS reports, makes starts
// idempotent and translates the executor's reports into IRGS_MOTION_REPORT (and, for a mission,
// MISSION_ITEM_REACHED / MISSION_CURRENT). Pure: FirmwareCore passes the step input and the
// safety state and sends the messages it takes (docs/protocol.md sections 11, 13, 15 and 17).
//
// Idempotent starts: a start whose primitive id (param 7, IRGS_WAYPOINTS.id) is one of the last
// kHistory ids is not started again; its first answer (MAV_RESULT) is repeated and the current
// status sent, so a retried COMMAND_LONG whose ack was lost, or a late retry that crosses a newer
// start, changes nothing. A command without an id (0: generic ground stations) gets one from
// kFirstRobotId up; its retry (confirmation > 0, same command and parameters) is recognised too.
//
// Missions: the stored waypoints from the robot's position become the thesis traveling legs
// (missionLegs: repeated and collinear waypoints merged), run as SEGMENTS primitives of at most
// motion::kMaxWaypoints legs one after the other under one id; reports carry mission item
// numbers. A mission of more than 32 legs is thus not refused, and the executor keeps its fixed
// size (32 points, no heap).

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "comms/mavlink/messages.hpp"
#include "core/motion/motion_executor.hpp"
#include "core/robot/robot_profile.hpp"

namespace irgs::app {

// What the firmware's safety rules allow at the moment of a start.
struct MotionPermit {
  bool estop = false;            // latched: DENIED, kRefused(kSafety)
  bool gcs_alive = true;         // no ground station: TEMPORARILY_REJECTED, kRefused(kSafety)
  bool forward_blocked = false;  // a forward bumper pressed: a forward DRIVE is refused (kBumped)
  bool reverse_blocked = false;
};

using MotionMessage =
    std::variant<comms::mavlink::IrgsMotionReport, comms::mavlink::IrgsBehaviourStatus,
                 comms::mavlink::MissionItemReached, comms::mavlink::MissionCurrent,
                 comms::mavlink::Statustext>;

// A stored mission's part to run (MAV_CMD_MISSION_START).
struct MissionRequest {
  std::vector<Vec2> waypoints;   // the items first..last, our world frame
  std::uint16_t first_item = 0;  // mission item number of waypoints[0]
  std::uint16_t total_items = 0;
  std::uint32_t mission_id = 0;  // MISSION_CURRENT.mission_id
};

class FirmwareMotion {
 public:
  static constexpr std::uint16_t kFirstRobotId = 0x8000;  // ids the robot picks: 32768-65535
  static constexpr std::size_t kHistory = 8;

  // `status_period_s`: IRGS_BEHAVIOUR_STATUS while a primitive runs (> 0).
  FirmwareMotion(const RobotProfile& profile, double status_period_s);
  FirmwareMotion(const FirmwareMotion&) = delete;
  FirmwareMotion& operator=(const FirmwareMotion&) = delete;

  // MAX_SPEED / MAX_TURN_RATE: the defaults are half of them (as the behaviours before), the
  // spec's speeds are capped at them and so is every wheel command, at once while one runs.
  void setLimits(double max_speed_mps, double max_turn_rate_radps);
  void setStatusPeriod(double status_period_s);

  // MOVE_DISTANCE, TURN_ANGLE, FOLLOW_WALL: the MAV_RESULT to acknowledge with; nullopt for any
  // other command.
  std::optional<std::uint8_t> onCommand(const comms::mavlink::CommandLong& command,
                                        const motion::MotionInput& now, const MotionPermit& permit);
  // IRGS_WAYPOINTS (answered by its reports and status, not by an ack).
  void onWaypoints(const comms::mavlink::IrgsWaypoints& message, const motion::MotionInput& now,
                   const MotionPermit& permit);
  // MAV_CMD_MISSION_START on the stored mission: the MAV_RESULT.
  std::uint8_t startMission(const comms::mavlink::CommandLong& command,
                            const MissionRequest& mission, const motion::MotionInput& now,
                            const MotionPermit& permit);
  // MAV_CMD_IRGS_STOP with a primitive id: cancels it when it runs; an id never seen is
  // recorded as cancelled (reported kCancelled), so its start arriving later (a lost start
  // retried after the stop) does not run.
  void stop(std::uint16_t id, const motion::MotionInput& now);
  // STOP without an id, the operator's teleop, a cleared mission: kCancelled.
  void cancel(const motion::MotionInput& now);
  // A firmware safety stop (e-stop, ground station silent): kFailed(reason).
  void abort(motion::Reason reason, const motion::MotionInput& now);

  // One control period: the wheel command to hold until the next (zero when idle), capped at
  // the limits. Queues the reports of the step and the periodic status.
  VelocityCommand step(const motion::MotionInput& input);
  // MAV_CMD_REQUEST_MESSAGE(IRGS_BEHAVIOUR_STATUS): the status now.
  void requestStatus(double time_s);

  bool running() const { return executor_.running(); }
  bool missionRunning() const { return running() && mission_.has_value(); }
  const motion::MotionExecutor& executor() const { return executor_; }
  std::vector<MotionMessage> takeMessages();

 private:
  struct Current {  // what IRGS_BEHAVIOUR_STATUS says
    std::uint16_t id = 0;
    motion::PrimitiveKind kind = motion::PrimitiveKind::kTurn;
    std::uint16_t command = 0;  // MAV_CMD that started it (0: IRGS_WAYPOINTS)
    comms::mavlink::IrgsBehaviourState state = comms::mavlink::IrgsBehaviourState::kIdle;
    motion::ReportKind last = motion::ReportKind::kStarted;
    motion::Reason reason = motion::Reason::kNone;
    std::int16_t index = -1;
    double distance = 0.0;
    double sign = 1.0;  // progress signed like the command (a clockwise turn: negative)
  };
  struct Answer {  // a start's first answer, repeated for its retries
    std::uint16_t id = 0;
    std::uint8_t result = 0;
  };
  struct MissionRun {
    std::vector<Vec2> points;              // turning points (leg ends), in order
    std::vector<std::uint16_t> last_item;  // per leg: the last mission item it reaches
    std::size_t chunk_start = 0;           // first leg of the running SEGMENTS primitive
    int reported = -1;                     // highest item reported reached
    std::size_t legs_done = 0;
    std::uint16_t total_items = 0;
    std::uint32_t mission_id = 0;
    double distance_done = 0.0;  // of the chunks already finished
  };

  std::optional<std::uint8_t> repeatedAnswer(std::uint16_t id,
                                             const comms::mavlink::CommandLong* command) const;
  void remember(std::uint16_t id, std::uint8_t result, const comms::mavlink::CommandLong* command);
  std::uint16_t nextRobotId();
  // Starts `primitive` (spec speeds capped), reporting kStarted or kRefused. The MAV_RESULT.
  std::uint8_t begin(motion::Primitive primitive, std::uint16_t command,
                     const motion::MotionInput& now, const MotionPermit& permit,
                     std::optional<MissionRun> mission);
  // The MAV_RESULT and reason when the safety rules refuse `primitive` now.
  std::optional<std::uint8_t> refusalResult(const motion::Primitive& primitive,
                                            const MotionPermit& permit,
                                            motion::Reason& reason) const;
  void refuse(std::uint16_t id, motion::PrimitiveKind kind, std::uint16_t command,
              motion::Reason reason, const motion::MotionInput& now);
  void capSpeeds(motion::PrimitiveSpec& spec) const;
  bool startChunk(const motion::MotionInput& now);
  void drain(const motion::MotionInput& at);
  // Mission bookkeeping of one report; false when the report is internal (a chunk's end/start).
  bool translateMission(motion::MotionReport& report, const motion::MotionInput& at);
  void sendMissionCurrent(std::size_t leg);
  void publish(const motion::MotionReport& report, bool of_mission);
  void sendStatus(double time_s);
  void say(std::uint8_t severity, const std::string& text);

  motion::MotionExecutor executor_;
  double max_speed_mps_;
  double max_turn_rate_radps_;
  double status_period_s_;
  double next_status_s_ = 0.0;
  Current current_;
  std::array<Answer, kHistory> answers_{};
  std::size_t answer_next_ = 0;
  std::optional<comms::mavlink::CommandLong> anonymous_;  // the last start without an id
  std::uint8_t anonymous_result_ = 0;
  std::uint16_t next_robot_id_ = kFirstRobotId;
  std::optional<MissionRun> mission_;
  std::vector<MotionMessage> out_;
};

}  // namespace irgs::app
