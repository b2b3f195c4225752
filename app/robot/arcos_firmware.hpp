#pragma once
// The virtual Pioneer: the core simulator served as an ARCOS server (what MobileSim/AMRISim and
// a real Pioneer's microcontroller do), pure (no I/O, no clock). The owner feeds it the bytes a
// client wrote and the time, calls advance(now) and writes what takeOutput() returns.
//
// Server protocol (Pioneer 3 Operations Manual, "Client-server communication"):
//   SYNC0, SYNC1, SYNC2 are echoed in order (SYNC2's answer carries name, class, subclass);
//   OPEN (1) starts the SIP stream every sip_period_s, CLOSE (2) stops it and the motors.
//   While open: PULSE (0) and every other command reset the watchdog; ENABLE, SETO, VEL, RVEL,
//   VEL2, HEAD, DHEAD, MOVE, SONAR, STOP, ESTOP act on the simulator; other commands are
//   counted and ignored. When nothing arrives for watchdog_s the motors stop (ARCOS's
//   watchdog, 2 s by default); the next motion command moves again.
//
// Strict mode (`irgs-robot --protocol arcos --strict`) also does what the Pioneer manuals say a
// real robot does with a client that does not keep the rules (docs/pioneer.md, "Strict mode"):
//   * one command per packet: a payload that is not exactly one command with at most one
//     argument is ignored ("unrecognized or otherwise malformed client commands ... get
//     ignored by the server", ARIA overview), as is a packet with a byte count above 249
//     ("Maximum of 249", Pioneer 2/3 Operations Manual, client command packet protocol);
//   * the command processor: "limit client commands to a maximum of one every 3-5 milliseconds
//     or be prepared to recover from lost commands" (same manual, AROS chapter): a command
//     arriving less than kStrictCommandSpacing_s (5 ms) after the previous one it took is lost;
//     packets of one read are spread at link_baud's byte time when it is known (a pty), at one
//     instant otherwise (TCP);
//   * the watchdog counts only commands it took: none for watchdog_s halts the motors, and the
//     next command resumes the last speed and heading set points ("If the robot shuts down due
//     to lack of communication with the client, it will revive upon receipt of a client command
//     and automatically accelerate to the last-specified speed and heading", AmigoBot and
//     Pioneer 3 manuals) where the lenient mode clears them.
// Both modes count command packets per second on arrival (stats().peak_commands_per_s).
//
// SIP positions are the simulator's odometry relative to the last SETO, in DistConvFactor units,
// wrapped to 15 bits as ARCOS does; sonar readings are those taken during the cycle (the last
// one of each disc), RangeConvFactor units, max range when there was no echo.

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "app/robot/arrival_rate_meter.hpp"
#include "comms/arcos/arcos_packet.hpp"
#include "comms/robot/arcos_params.hpp"
#include "core/sim/simulator.hpp"

namespace irgs::app {

struct ArcosFirmwareConfig {
  std::string name = "irgs-robot";
  std::string robot_class = "Pioneer";
  std::optional<std::string> subclass;  // default: the profile's arcos.subclass
  std::optional<double> sip_period_s;   // default: the profile's arcos.sip_cycle_ms
  std::optional<double> watchdog_s;     // default: the profile's arcos.watchdog_s (2 s)
  bool motors_enabled_at_start = true;  // as MobileSim; a real P3 waits for ENABLE 1
  bool strict = false;                  // drop and count what a real robot would (see above)
  // Baud of the serial line the bytes come over (irgs-robot on a pty, or behind a TCP bridge
  // with --baud): strict mode spreads the packets of one read at its byte time. Empty: they
  // arrive together (TCP).
  std::optional<std::uint32_t> link_baud;
};

// Strict mode's command processor: a command closer than this to the previous one is lost.
inline constexpr double kStrictCommandSpacing_s = 0.005;
// MOVE's speed until a SETV sets it (m/s).
inline constexpr double kMoveSpeed_mps = 0.4;
// Strict mode: the largest byte count a client command packet may announce.
inline constexpr std::size_t kStrictMaxByteCount = 249;

enum class ArcosServerState { kWaitSync0, kWaitSync1, kWaitSync2, kSynced, kOpen };

struct ArcosFirmwareStats {
  std::uint64_t commands = 0;             // command packets taken while open
  std::uint64_t unknown_commands = 0;     // well-formed, not handled
  std::uint64_t bad_commands = 0;         // malformed: parseCommand rejected (strict: or too long)
  std::uint64_t too_soon = 0;             // strict: lost, closer than 5 ms to the previous command
  std::uint32_t peak_commands_per_s = 0;  // command packets arriving while open, most in 1 s
  std::uint64_t sips = 0;
  std::uint32_t watchdog_stops = 0;
  std::uint32_t opens = 0;
  comms::arcos::PacketCounters packets;
};

class ArcosFirmware {
 public:
  // Throws std::invalid_argument for non-positive periods.
  ArcosFirmware(Simulator sim, ArcosFirmwareConfig config = {});

  // The bytes of one read, taken at now_s. earliest_s: when the reader last looked, if the bytes
  // may have arrived any time since (a late poll); without it they came just before now_s.
  void receiveBytes(std::span<const std::uint8_t> bytes, double now_s,
                    std::optional<double> earliest_s = std::nullopt);
  // Steps the simulator up to now_s and emits the SIPs that fall due.
  void advance(double now_s);
  std::vector<std::uint8_t> takeOutput();

  const Simulator& simulator() const { return sim_; }
  ArcosServerState state() const { return state_; }
  const ArcosFirmwareStats& stats() const { return stats_; }
  // Command packets that arrived while open (accepted or not), by arrival time.
  const ArrivalRateMeter& commandRate() const { return command_rate_; }
  const comms::ArcosParams& params() const { return params_; }
  const ArcosFirmwareConfig& config() const { return config_; }
  bool motorsEnabled() const { return motors_enabled_; }
  // The pose a SIP reports now (odometry relative to the SETO origin), metres/radians.
  Pose2 reportedPose() const;

 private:
  enum class Heading { kFree, kRate, kTarget };
  void onPacket(std::span<const std::uint8_t> payload, double now_s);
  void onHandshake(std::uint8_t number, double now_s);
  void onCommand(std::uint8_t command, std::optional<int> argument, double now_s);
  void reply(std::span<const std::uint8_t> payload);
  void stopMotion(bool brake);
  void tripWatchdog();
  void applyControl();
  void collectSonar(const TelemetrySample& sample);
  void sendSip();

  Simulator sim_;
  ArcosFirmwareConfig config_;
  comms::ArcosParams params_;
  double sip_period_s_ = 0.1;
  double watchdog_s_ = 2.0;
  ArcosServerState state_ = ArcosServerState::kWaitSync0;
  comms::arcos::PacketDecoder decoder_;
  std::vector<comms::arcos::Packet> packets_;
  std::vector<double> arrival_scratch_;   // receiveBytes: each packet's arrival time
  std::optional<double> last_arrival_s_;  // the newest packet's (serial line: link_baud)
  std::vector<std::uint8_t> output_;
  ArcosFirmwareStats stats_;

  bool motors_enabled_ = true;
  bool sonar_enabled_ = true;
  double last_command_s_ = 0.0;
  std::optional<double> last_taken_s_;  // strict: arrival of the last command processed
  ArrivalRateMeter command_rate_;
  bool watchdog_tripped_ = false;
  double next_sip_s_ = 0.0;
  // Motion set points: translational velocity or a MOVE goal; rotational velocity or a heading.
  double velocity_mps_ = 0.0;
  std::optional<double> move_remaining_m_;  // MOVE: distance left, signed
  double move_speed_mps_ = kMoveSpeed_mps;  // SETV
  Pose2 move_last_pose_;
  Heading heading_mode_ = Heading::kFree;
  double rot_velocity_radps_ = 0.0;
  double heading_target_rad_ = 0.0;                   // odometry heading in the SETO frame
  Pose2 origin_;                                      // odometry pose at the last SETO
  std::vector<std::optional<double>> sonar_cycle_m_;  // per disc: reading this cycle (nullopt:
                                                      // none), max range for no echo
  TelemetrySample sample_;
};

}  // namespace irgs::app
