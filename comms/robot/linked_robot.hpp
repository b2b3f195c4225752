#pragma once
// The second adapter of irgs::Robot: a robot behind a MAVLink link (comms::Link). The ground
// station drives it exactly like the in-process simulator; it never knows which one it has.
//
// Threading: the Link delivers frames on the io thread; LinkedRobot converts them to
// TelemetrySamples under a mutex and update() (called from the GUI thread or the irgs-sim loop)
// drains them, oldest first. drive()/stop() store the command and a TeleopPacer decides when a
// MANUAL_CONTROL goes (teleop_pacer.hpp): a change at once but never two closer than
// teleop_min_interval_s (the newest wins; <= 18.2/s whatever the caller does), a non-zero
// command repeated every teleop_period_s (the firmware stops the motors when these stop
// arriving, docs/protocol.md section 11); stop() sends a zero MANUAL_CONTROL (at once, or when
// the interval allows) and IRGS_STOP as an acknowledged command.
//
// Samples: one TelemetrySample per odometry time stamp (LOCAL_POSITION_NED + ATTITUDE,
// ODOMETRY or IRGS_POSE_2D), with the sonar readings (DISTANCE_SENSOR / IRGS_SONAR_SCAN) of that
// time stamp and the newest encoder ticks, bumper bits and proximity ranges; see
// comms/robot/telemetry_assembler.hpp for when a sample is complete. time_s is the robot's boot
// time in seconds (it starts over when the robot restarts). Link state, statistics and console
// events are available through linkState(), linkStats() and takeEvents() for the parts of the
// application that show them.
//
// Link loss: the firmware stops on its own when our heartbeats or MANUAL_CONTROLs stop arriving;
// the commanded velocity is then cleared here too (an event says so), so a robot that comes back
// does not start moving on an old command: the operator (or script) drives it again.

#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "comms/link/link.hpp"
#include "comms/link/link_url.hpp"
#include "comms/mavlink/messages.hpp"
#include "comms/robot/linked_motion.hpp"
#include "comms/robot/message_sampler.hpp"
#include "comms/robot/param_client.hpp"
#include "comms/robot/telemetry_assembler.hpp"
#include "core/robot/robot.hpp"

namespace irgs::comms {

struct LinkedRobotConfig {
  LinkConfig link{};
  double teleop_period_s = 0.1;  // MANUAL_CONTROL repeat period while moving (10 Hz)
  // Never two MANUAL_CONTROLs closer than this (<= teleop_period_s): at most 18.2/s, under the
  // 20/s cap of issue 24 with room for arrival jitter.
  double teleop_min_interval_s = 0.055;
  // Samples kept while nobody calls update(); older ones are dropped (and counted).
  std::size_t max_pending_samples = 2000;
  // How telemetry frames become samples (release on pose or by time stamp, hold time).
  TelemetryAssemblerConfig telemetry{};
  // Console events kept while nobody calls takeEvents(); older ones are dropped.
  std::size_t max_pending_events = 1000;
  // Decoded messages for takeMessages() (the GUI's plots): off unless max_rate_hz > 0.
  MessageSamplerConfig messages{};
  // Motion primitives run on the firmware (motionControl(), mavlink_motion_client.hpp).
  MotionClientConfig motion{};
};

// What a behaviour command asks of the firmware (dialect COMMAND_LONG ids 48100-48104).
enum class RobotBehaviourKind { kMoveDistance, kTurnAngle, kFollowWall, kStop, kEmergencyStop };
struct RobotBehaviourCommand {
  RobotBehaviourKind kind = RobotBehaviourKind::kStop;
  double distance_m = 0.0;  // kMoveDistance (signed), kFollowWall (wall distance)
  double angle_rad = 0.0;   // kTurnAngle (CCW positive)
  double speed_mps = 0.0;   // 0: firmware default
  bool wall_on_left = false;
  double turn_rate_radps = 0.0;  // kTurnAngle: 0 = firmware default
  double travel_m = 0.0;         // kFollowWall: stop after this path length, 0 = no limit
  bool engage = true;            // kEmergencyStop: false releases a latched e-stop
};

// The MANUAL_CONTROL that asks for `command` (docs/protocol.md section 4): x = v / max_speed,
// r = -omega / max_turn_rate (MAVLink yaw is clockwise-positive), both scaled to +-1000,
// rounded and clamped. Throws std::invalid_argument for a non-finite command or limits <= 0.
mavlink::ManualControl manualControlFor(const VelocityCommand& command, const MotionLimits& limits,
                                        std::uint8_t target_system = 0);
// The dialect COMMAND_LONG for a behaviour (ids 48100-48104, params as resources/mavlink/irgs.xml
// defines them). Throws std::invalid_argument for non-finite or negative-where-unsigned values.
mavlink::CommandLong behaviourCommandLong(const RobotBehaviourCommand& command,
                                          std::uint8_t target_system = 0);

class LinkedRobot final : public Robot {
 public:
  struct OpenResult {
    std::unique_ptr<LinkedRobot> robot;  // null when error is set
    std::string error;
  };
  // Creates the link and starts connecting; it reconnects on its own from then on.
  static OpenResult open(IoThread& io, const LinkUrl& url, RobotProfile profile,
                         LinkedRobotConfig config = {});
  ~LinkedRobot() override;

  // Robot
  const RobotProfile& profile() const override;
  std::string describe() const override;  // e.g. "serial:///dev/pts/3?baud=115200 (connected)"
  // Throws std::invalid_argument for a non-finite velocity (as the simulator does).
  void drive(const VelocityCommand& command) override;
  void stop() override;
  std::vector<TelemetrySample> update(double wall_elapsed_s) override;
  // Closes the link and releases the sample the assembler still holds (and late readings).
  std::vector<TelemetrySample> finish() override;
  // The firmware runs every primitive kind (docs/protocol.md section 18).
  MotionControl* motionControl() override;

  // Link-specific, for the link-health panel, the console and irgs-sim.
  LinkState linkState() const;
  LinkStats linkStats() const;
  std::vector<LinkEvent> takeEvents();  // link events + STATUSTEXT, oldest first
  std::uint64_t droppedSamples() const;
  // The robot's messages, every numeric field, thinned per stream (config.messages), oldest
  // first; robot_time_s is the robot's boot clock, as TelemetrySample::time_s before update()
  // hands it on. Empty when config.messages is off.
  std::vector<MessageSample> takeMessages();
  MessageSamplerCounters messageCounters() const;
  // Sends a behaviour command (acknowledged, retried); `done` runs on the io thread. Throws
  // std::invalid_argument for an invalid command (behaviourCommandLong) before sending anything.
  void sendBehaviour(const RobotBehaviourCommand& command, CommandCallback done = {});

  // Firmware parameters (MAVLink parameter protocol, comms/robot/param_client.hpp): read all,
  // write one (confirmed by the robot's PARAM_VALUE). Thread-safe; the answers arrive on the io
  // thread and are read with firmwareParams() / takeParamResults().
  void requestParams();
  // Throws std::invalid_argument for a bad name or a non-finite value (nothing is sent).
  void setParam(const std::string& name, double value);
  std::vector<ParamEntry> firmwareParams() const;
  int firmwareParamCount() const;  // param_count the robot announced (0 before any)
  bool readingParams() const;
  std::vector<ParamWriteResult> takeParamResults();

  struct State;  // shared with io-thread callbacks (linked_robot.cpp)

 private:
  LinkedRobot(RobotProfile profile, std::string url_text, LinkedRobotConfig config);
  RobotProfile profile_;
  std::string url_text_;
  LinkedRobotConfig config_;
  std::shared_ptr<State> state_;
  std::shared_ptr<LinkedMotion> motion_;
  std::unique_ptr<Link> link_;
  std::optional<double> tx_budget_bytes_per_s_;  // from the URL's baud (LinkStats)
};

}  // namespace irgs::comms
