#pragma once
// The virtual robot firmware: a core Simulator behind a MAVLink 2 interface, with the firmware
// safety rules of docs/protocol.md ("Firmware safety rules"). Pure: no Asio, no threads, no
// clock. The caller passes the firmware time `now_s` (seconds since boot, non-decreasing), feeds
// received bytes and writes out the bytes takeOutput() returns. Behaviours: MOVE_DISTANCE and
// TURN_ANGLE (closed loop on odometry); FOLLOW_WALL is answered UNSUPPORTED.
//
// Frames (see docs/protocol.md):
//  * Our world frame is x forward (at start), y left, z up, theta counter-clockwise (FLU).
//    MAVLink local frames are z-down (docs/protocol.md section 3): ODOMETRY and
//    LOCAL_POSITION_NED use MAV_FRAME_LOCAL_NED with world x as north, i.e. the rotation by pi
//    about x: x_ned = x, y_ned = -y, z_ned = 0, yaw = -theta, yawspeed = -omega; the ODOMETRY
//    twist is in MAV_FRAME_BODY_FRD (vx = v forward).
//  * MANUAL_CONTROL: x in [-1000, 1000] forward -> v = x / 1000 * max_speed; r in
//    [-1000, 1000] positive = yaw clockwise (to the right) -> omega = -r / 1000 * max_turn_rate
//    (our omega is counter-clockwise positive).
//  * DISTANCE_SENSOR orientation: the sonar heading (CCW) as MAV_SENSOR_ROTATION_YAW_* (which
//    counts clockwise): heading +90 deg (left) -> YAW_270, -90 deg (right) -> YAW_90.

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "comms/mavlink/frame.hpp"
#include "comms/mavlink/frame_decoder.hpp"
#include "comms/mavlink/frame_encoder.hpp"
#include "comms/mavlink/messages.hpp"
#include "core/robot/telemetry.hpp"
#include "core/sim/simulator.hpp"

namespace irgs::app {

struct FirmwareConfig {
  std::uint8_t system_id = 1;
  std::uint8_t component_id = 1;  // MAV_COMP_ID_AUTOPILOT1
  // Telemetry periods [s]; 0 disables the stream (heartbeat excepted: it is always sent).
  double heartbeat_period_s = 1.0;
  // Pose stream: LOCAL_POSITION_NED + ATTITUDE (generic ground stations), ODOMETRY,
  // IRGS_ENCODER_TICKS and, when enabled, IRGS_POSE_2D.
  double odometry_period_s = 0.05;
  // Sonar: each fresh reading as DISTANCE_SENSOR (batched per period), and IRGS_SONAR_SCAN when
  // enabled.
  double sonar_period_s = 0.05;
  double contact_period_s = 0.1;  // IRGS_CONTACT (also sent at once when a bumper changes)
  // Streams. The defaults use ~89 % of a 115200 baud UART (docs/protocol.md, section 11);
  // the compact dialect streams are for slow links (switch ODOMETRY off there).
  bool send_odometry = true;
  bool send_local_position = true;
  bool send_pose_2d = false;
  bool send_sonar_scan = false;
  bool send_distance_sensor = true;
  bool send_encoder_ticks = true;
  // Safety rules. A MANUAL_CONTROL older than teleop_timeout_s no longer drives; with
  // heartbeats missing for gcs_timeout_s all motion stops. Safety stops brake at once.
  double teleop_timeout_s = 0.3;
  double gcs_timeout_s = 1.5;
};

// The compact profile for slow links (9600 baud HC-05 modules, docs/protocol.md sections 4-5):
// IRGS_POSE_2D at 10 Hz, IRGS_SONAR_SCAN at 5 Hz, IRGS_CONTACT at 1 Hz (and on change),
// HEARTBEAT; no ODOMETRY, LOCAL_POSITION_NED, ATTITUDE, DISTANCE_SENSOR or encoder ticks.
// About 640 B/s of the 960 B/s a 9600 baud UART moves.
FirmwareConfig slowLinkFirmwareConfig(FirmwareConfig base = {});

// Why the motors are (or are not) allowed to move, for tests and the console.
struct SafetyState {
  bool gcs_alive = false;      // a ground-station heartbeat within gcs_timeout_s
  bool teleop_active = false;  // a MANUAL_CONTROL within teleop_timeout_s
  bool estop_latched = false;
  std::uint32_t bumpers = 0;  // pressed bumpers of the last step
  bool forward_blocked = false;
  bool reverse_blocked = false;
};

class FirmwareCore {
 public:
  // Throws std::invalid_argument for non-positive timeouts or negative periods.
  FirmwareCore(Simulator simulator, FirmwareConfig config = {});

  // Decodes bytes from the ground station and acts on the messages they carry.
  void receiveBytes(std::span<const std::uint8_t> bytes, double now_s);
  // Acts on one decoded message (frames from our own system id are ignored: echo protection).
  void receive(const comms::mavlink::Frame& frame, double now_s);
  // Steps the simulator up to now_s (whole steps of its dt), enforcing the safety rules at every
  // step, and queues the telemetry that falls due.
  void advance(double now_s);

  // The encoded frames queued since the last call, in order.
  std::vector<std::uint8_t> takeOutput();
  std::size_t pendingOutputBytes() const { return output_.size(); }

  SafetyState safety() const;
  const Simulator& simulator() const { return sim_; }
  const FirmwareConfig& config() const { return config_; }
  const comms::mavlink::DecodeCounters& decodeTotals() const { return decoder_.totals(); }

 private:
  template <class M>
  void send(const M& message);
  void sendStatus(std::uint8_t severity, const std::string& text);
  void handleCommand(const comms::mavlink::CommandLong& command);
  void applySafety();
  void safetyStop(const std::string& reason);
  void sendTelemetry(const TelemetrySample& sample);
  void sendOdometry(const TelemetrySample& sample);
  void sendOdometryMessage(const TelemetrySample& sample);
  void sendSonar(const TelemetrySample& sample);
  void sendContact(const TelemetrySample& sample);
  void sendHeartbeat();
  // Behaviours (MAV_CMD_IRGS_MOVE_DISTANCE / TURN_ANGLE): closed loop on odometry.
  std::uint8_t startBehaviour(const comms::mavlink::CommandLong& command);
  void endBehaviour(comms::mavlink::IrgsBehaviourState state);
  std::optional<VelocityCommand> behaviourCommand();
  void sendBehaviourStatus();

  Simulator sim_;
  FirmwareConfig config_;
  comms::mavlink::FrameDecoder decoder_;
  comms::mavlink::FrameEncoder encoder_;
  std::vector<comms::mavlink::Frame> frames_;
  std::vector<std::uint8_t> output_;
  TelemetrySample sample_;

  // Safety state.
  std::optional<double> last_gcs_heartbeat_s_;
  std::optional<double> last_teleop_s_;
  VelocityCommand teleop_;
  bool estop_ = false;
  bool gcs_was_alive_ = false;
  bool teleop_was_active_ = false;
  bool warned_no_gcs_ = false;
  std::uint32_t bumpers_ = 0;

  // The running (or last) behaviour.
  struct Behaviour {
    std::uint16_t command = 0;  // 0: none yet
    comms::mavlink::IrgsBehaviourState state = comms::mavlink::IrgsBehaviourState::kIdle;
    double target = 0.0;    // signed distance [m] or angle [rad]
    double speed = 0.0;     // magnitude [m/s] or [rad/s]
    double progress = 0.0;  // signed, same unit as target
    Pose2 last_pose;        // odometry pose at the previous step
  };
  Behaviour behaviour_;
  double next_behaviour_status_s_ = 0.0;

  // Telemetry schedule (firmware time of the next send) and sonar accumulation.
  double next_heartbeat_s_ = 0.0;
  double next_odometry_s_ = 0.0;
  double next_sonar_s_ = 0.0;
  double next_contact_s_ = 0.0;
  std::vector<std::optional<SonarReading>> fresh_sonar_;  // newest unsent reading per sonar
  std::vector<SonarReading> last_sonar_;                  // newest reading per sonar (scan)
  double last_sonar_time_s_ = 0.0;
};

}  // namespace irgs::app
