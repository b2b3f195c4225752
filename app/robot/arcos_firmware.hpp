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
// SIP positions are the simulator's odometry relative to the last SETO, in DistConvFactor units,
// wrapped to 15 bits as ARCOS does; sonar readings are those taken during the cycle (the last
// one of each disc), RangeConvFactor units, max range when there was no echo.

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

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
};

enum class ArcosServerState { kWaitSync0, kWaitSync1, kWaitSync2, kSynced, kOpen };

struct ArcosFirmwareStats {
  std::uint64_t commands = 0;          // packets received while open
  std::uint64_t unknown_commands = 0;  // well-formed, not handled
  std::uint64_t bad_commands = 0;      // payloads parseCommand rejected
  std::uint64_t sips = 0;
  std::uint32_t watchdog_stops = 0;
  std::uint32_t opens = 0;
  comms::arcos::PacketCounters packets;
};

class ArcosFirmware {
 public:
  // Throws std::invalid_argument for non-positive periods.
  ArcosFirmware(Simulator sim, ArcosFirmwareConfig config = {});

  void receiveBytes(std::span<const std::uint8_t> bytes, double now_s);
  // Steps the simulator up to now_s and emits the SIPs that fall due.
  void advance(double now_s);
  std::vector<std::uint8_t> takeOutput();

  const Simulator& simulator() const { return sim_; }
  ArcosServerState state() const { return state_; }
  const ArcosFirmwareStats& stats() const { return stats_; }
  const comms::ArcosParams& params() const { return params_; }
  bool motorsEnabled() const { return motors_enabled_; }
  // The pose a SIP reports now (odometry relative to the SETO origin), metres/radians.
  Pose2 reportedPose() const;

 private:
  enum class Heading { kFree, kRate, kTarget };
  void onPacket(std::span<const std::uint8_t> payload, double now_s);
  void onCommand(std::uint8_t command, std::optional<int> argument, double now_s);
  void reply(std::span<const std::uint8_t> payload);
  void stopMotion(bool brake);
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
  std::vector<std::uint8_t> output_;
  ArcosFirmwareStats stats_;

  bool motors_enabled_ = true;
  bool sonar_enabled_ = true;
  double last_command_s_ = 0.0;
  bool watchdog_tripped_ = false;
  double next_sip_s_ = 0.0;
  // Motion set points: translational velocity or a MOVE goal; rotational velocity or a heading.
  double velocity_mps_ = 0.0;
  std::optional<double> move_remaining_m_;  // MOVE: distance left, signed
  Pose2 move_last_pose_;
  Heading heading_mode_ = Heading::kFree;
  double rot_velocity_radps_ = 0.0;
  double heading_target_rad_ = 0.0;                   // odometry heading in the SETO frame
  Pose2 origin_;                                      // odometry pose at the last SETO
  std::vector<std::optional<double>> sonar_cycle_m_;  // per disc: reading this cycle (nullopt:
                                                      // none), max range for no echo
  double stalled_s_ = 0.0;
  TelemetrySample sample_;
};

}  // namespace irgs::app
