#pragma once
// The virtual robot firmware: a core Simulator behind a MAVLink 2 interface, with the firmware
// safety rules of docs/protocol.md ("Firmware safety rules"). Pure: no Asio, no threads, no
// clock. The caller passes the firmware time `now_s` (seconds since boot, non-decreasing), feeds
// received bytes and writes out the bytes takeOutput() returns. Behaviours: the robot-side motion
// primitives (core/motion) through one MotionExecutor (firmware_motion.hpp): MOVE_DISTANCE,
// TURN_ANGLE, FOLLOW_WALL, IRGS_WAYPOINTS and missions (an uploaded path run as the thesis
// traveling algorithm), stepped on the firmware's own telemetry, reported in IRGS_MOTION_REPORT
// and IRGS_BEHAVIOUR_STATUS. Parameters
// (PARAM_*, firmware_params.hpp), per-message stream intervals (MAV_CMD_SET_MESSAGE_INTERVAL),
// SYS_STATUS and SCALED_IMU as docs/protocol.md sections 12-14 describe.
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
#include <memory>
#include <optional>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "app/robot/firmware_mission.hpp"
#include "app/robot/firmware_motion.hpp"
#include "app/robot/firmware_params.hpp"
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
  double imu_period_s = 0.1;      // SCALED_IMU
  double status_period_s = 1.0;   // SYS_STATUS
  // IRGS_BEHAVIOUR_STATUS while a primitive runs (and at once on every change).
  double behaviour_status_period_s = 0.5;
  // Streams. The defaults use ~93 % of a 115200 baud UART (docs/protocol.md, section 11);
  // the compact dialect streams are for slow links (switch ODOMETRY off there).
  bool send_odometry = true;
  bool send_local_position = true;
  bool send_pose_2d = false;
  bool send_sonar_scan = false;
  bool send_distance_sensor = true;
  bool send_encoder_ticks = true;  // not for a three-caster robot (it has no left/right wheels)
  // Floor sensors (IRGS_MOUSE_COUNTS) and caster encoders (IRGS_CASTER_ENCODERS), with the pose
  // stream, when the robot has them (a drive/mouse_sensors rig; drive type "three_caster").
  bool send_mouse_counts = true;
  bool send_caster_encoders = true;
  // Safety rules. A MANUAL_CONTROL older than teleop_timeout_s no longer drives; with
  // heartbeats missing for gcs_timeout_s all motion stops. Safety stops brake at once.
  double teleop_timeout_s = 0.3;
  double gcs_timeout_s = 1.5;
  // SCALED_IMU noise (white, seeded): gyro [rad/s] and accelerometer [m/s^2], 1 sigma.
  std::uint64_t imu_seed = 1;
  double gyro_noise_radps = 0.003;
  double accel_noise_mps2 = 0.05;
  // The virtual battery behind SYS_STATUS: a linear discharge curve from full_v to empty_v over
  // capacity_ah, drawing idle_a plus a_per_mps * |v| plus a_per_radps * |omega|.
  double battery_capacity_ah = 2.2;
  double battery_full_v = 12.6;
  double battery_empty_v = 10.5;
  double battery_idle_a = 0.25;
  double battery_a_per_mps = 2.0;
  double battery_a_per_radps = 0.4;
  // MAVLink signing (docs/protocol.md, "Who may drive"). With a key every frame sent is signed
  // and receiveBytes() acts only on frames signed with it: unsigned, wrongly signed and replayed
  // frames are dropped at intake, counted (refusedFrames(), SYS_STATUS errors_comm) and reported
  // by a STATUSTEXT warning at most every refusal_report_period_s.
  std::optional<comms::mavlink::SigningKey> signing_key;
  // The signing time (signingTimestampAt: 10 us units since 2015) at firmware time 0, i.e. the
  // owner's wall clock at boot; the firmware's signing clock is this plus its own time.
  std::uint64_t signing_time_at_boot = 0;
  double refusal_report_period_s = 5.0;
};

// The compact profile for slow links (9600 baud HC-05 modules, docs/protocol.md sections 4-5):
// IRGS_POSE_2D at 10 Hz, IRGS_SONAR_SCAN at 5 Hz, IRGS_CONTACT at 1 Hz (and on change),
// HEARTBEAT; no ODOMETRY, LOCAL_POSITION_NED, ATTITUDE, DISTANCE_SENSOR, encoder ticks, floor
// sensor counts or caster encoders.
// SYS_STATUS at 0.2 Hz, no SCALED_IMU, IRGS_BEHAVIOUR_STATUS at 0.5 Hz while a primitive runs.
// About 700 B/s of the 960 B/s a 9600 baud UART moves.
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

  // Decodes bytes from the ground station and acts on the messages they carry (with a signing
  // key: only on frames signed with it).
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
  // Frames refused by the signature check (unsigned, wrong key, replayed) since boot.
  std::uint64_t refusedFrames() const;
  // Queues a STATUSTEXT warning for the ground station (irgs-robot: a second client refused).
  void warnGroundStation(const std::string& text);
  const ParamTable& params() const { return params_; }
  const MissionStore& mission() const { return mission_store_; }
  const FirmwareMotion& motion() const { return *motion_; }
  // The period of a streamed message [s] (0 = off), nullopt for messages that are not streams.
  std::optional<double> messagePeriod(std::uint32_t message_id) const;
  // State of charge of the virtual battery, 0..1.
  double batteryRemaining() const;

 private:
  // A periodic message; period 0 = off. default_period_s is the configured rate (the value
  // MAV_CMD_SET_MESSAGE_INTERVAL with interval 0 restores).
  struct Stream {
    std::uint32_t message_id = 0;
    ParamId group = ParamId::kRatePose;
    double default_period_s = 0.0;
    double period_s = 0.0;
    double next_s = 0.0;
  };
  template <class M>
  void send(const M& message);
  std::uint64_t signingTime(double t_s) const;
  void reportRefusedFrames(double now_s);
  void sendStatus(std::uint8_t severity, const std::string& text);
  void handleCommand(const comms::mavlink::CommandLong& command);
  void handleParam(const comms::mavlink::Frame& frame);
  void handleMission(const comms::mavlink::Frame& frame, double now_s);
  void sendMissionReply(const MissionReply& reply);
  void sendParam(ParamId id);
  void applyParam(ParamId id);
  std::uint8_t setMessageInterval(const comms::mavlink::CommandLong& command);
  void syncRateParams();
  Stream* findStream(std::uint32_t message_id);
  const Stream* findStream(std::uint32_t message_id) const;
  void applySafety();
  // Brakes at once and aborts the running primitive (kFailed(kSafety)).
  void safetyStop(const std::string& reason);
  void sendTelemetry(const TelemetrySample& sample);
  void sendStream(std::uint32_t message_id, const TelemetrySample& sample);
  void sendLocalPosition(const TelemetrySample& sample);
  void sendAttitude(const TelemetrySample& sample);
  void sendOdometryMessage(const TelemetrySample& sample);
  void sendPose2d(const TelemetrySample& sample);
  void sendEncoderTicks(const TelemetrySample& sample);
  void sendMouseCounts(const TelemetrySample& sample);
  void sendCasterEncoders(const TelemetrySample& sample);
  void sendDistanceSensors(const TelemetrySample& sample);
  void sendSonarScan();
  void sendContact(const TelemetrySample& sample);
  void sendScaledImu(const TelemetrySample& sample);
  void sendSysStatus();
  void sendHeartbeat();
  void updateImuAndBattery(double dt_s);
  double maxSpeed() const;
  double maxTurnRate() const;
  VelocityCommand teleopCommand() const;
  // Motion primitives (firmware_motion.hpp): the step input now, what the safety rules allow,
  // the messages to send.
  motion::MotionInput motionNow() const;
  MotionPermit motionPermit() const;
  std::uint8_t startMission(const comms::mavlink::CommandLong& command);
  std::uint8_t stopCommand(const comms::mavlink::CommandLong& command);
  void afterStart();
  void flushMotion();

  Simulator sim_;
  FirmwareConfig config_;
  comms::mavlink::FrameDecoder decoder_;
  comms::mavlink::FrameEncoder encoder_;
  std::vector<comms::mavlink::Frame> frames_;
  std::vector<std::uint8_t> output_;
  TelemetrySample sample_;
  ParamTable params_;
  MissionStore mission_store_;

  // Safety state.
  std::optional<double> last_gcs_heartbeat_s_;
  std::optional<double> last_teleop_s_;
  // MANUAL_CONTROL x and r as fractions [-1, 1] (r clockwise positive), scaled by MAX_SPEED and
  // MAX_TURN_RATE when applied, so a parameter change takes effect at once.
  double teleop_forward_ = 0.0;
  double teleop_yaw_cw_ = 0.0;
  bool estop_ = false;
  bool gcs_was_alive_ = false;
  bool teleop_was_active_ = false;
  bool warned_no_gcs_ = false;
  std::uint32_t bumpers_ = 0;
  std::uint64_t refused_reported_ = 0;  // refusedFrames() at the last STATUSTEXT about them
  double next_refusal_report_s_ = 0.0;

  // Every behaviour: one MotionExecutor (a pointer: it is neither copyable nor movable) and the
  // wheel command of its last step, held until the next.
  std::unique_ptr<FirmwareMotion> motion_;
  VelocityCommand motion_command_;

  // Telemetry schedule and sonar accumulation.
  double next_heartbeat_s_ = 0.0;
  std::vector<Stream> streams_;
  std::vector<std::optional<SonarReading>> fresh_sonar_;  // newest unsent reading per sonar
  std::vector<SonarReading> last_sonar_;                  // newest reading per sonar (scan)
  std::uint32_t scan_fired_ = 0;  // sonars that fired since the last IRGS_SONAR_SCAN
  double last_sonar_time_s_ = 0.0;
  // Worst floor-sensor state (MouseStatus order) of any step since the last IRGS_MOUSE_COUNTS.
  MouseStatus mouse_worst_right_ = MouseStatus::kTracking;
  MouseStatus mouse_worst_left_ = MouseStatus::kTracking;

  // IMU and battery models.
  std::mt19937_64 imu_rng_;
  std::normal_distribution<double> unit_normal_{0.0, 1.0};
  VelocityCommand last_true_velocity_;
  double accel_forward_mps2_ = 0.0;
  double battery_used_ah_ = 0.0;
  double battery_current_a_ = 0.0;
};

}  // namespace irgs::app
