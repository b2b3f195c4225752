#pragma once
// The client side of an ARCOS connection, pure (no I/O, no clock): the SYNC0/SYNC1/SYNC2
// handshake, OPEN, motor and sonar enabling, SIP-loss detection, and every command after OPEN
// paced by an ArcosCommandScheduler (changes only, keep-alive, <= 10 packets/s; see
// arcos_command_scheduler.hpp). The owner feeds it received packets and the time, calls tick()
// at least every 20 ms, and writes what takeOutgoing() returns.
//
//   kDisconnected --start()--> kSyncing: SYNC0 until echoed, then SYNC1, then SYNC2 (each
//     resent every sync_retry_s, or 2.5 round trips once an echo has shown a slower link;
//     after max_sync_attempts without progress: CLOSE, start over). Resending before the answer
//     can arrive is not harmless: after SYNC2 the robot reads 1 as OPEN and 2 as CLOSE, so a
//     second SYNC2 closes the connection the first one made.
//   SYNC2 reply (name, class, subclass) --> OPEN, then ENABLE 1 and SONAR 1 through the
//     scheduler --> kOpening
//   first standard SIP --> kConnected; the scheduler keeps the watchdog fed (a refreshed motion
//     command or PULSE whenever nothing went out for commands.keepalive_s)
//   no SIP for sip_timeout_s --> kLost; the handshake starts over on its own (a robot that
//     kept running answers the first SYNC0 with SIPs, so SIPs while syncing trigger CLOSE)
//   stop() --> CLOSE, kDisconnected.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "comms/arcos/arcos_command_scheduler.hpp"
#include "comms/arcos/arcos_packet.hpp"
#include "comms/arcos/arcos_sip.hpp"

namespace irgs::comms::arcos {

struct ArcosSessionConfig {
  double sync_retry_s = 0.3;
  int max_sync_attempts = 8;
  ArcosCommandSchedulerConfig commands{};  // rate cap, keep-alive (PULSE) and link baud
  double sip_timeout_s = 1.5;
  bool enable_motors = true;
  bool enable_sonar = true;
};

enum class ArcosState { kDisconnected, kSyncing, kOpening, kConnected, kLost };
const char* toString(ArcosState state);

struct ArcosEvent {
  double time_s = 0.0;
  ArcosState state = ArcosState::kDisconnected;
  bool warning = false;
  std::string text;
};

struct ArcosStats {
  std::uint64_t sips = 0;
  std::uint64_t other_packets = 0;  // config, IO, unknown types
  std::uint64_t bad_sips = 0;       // standard SIP type that did not parse
  std::uint32_t handshakes = 0;     // completed
  std::uint32_t losses = 0;
  std::optional<double> last_sip_s;
};

class ArcosClientSession {
 public:
  explicit ArcosClientSession(ArcosSessionConfig config = {});

  void start(double now_s);
  void stop(double now_s);
  void onPacket(const Packet& packet, double now_s);
  void tick(double now_s);

  // A one-shot command through the scheduler (only while open: kOpening/kConnected; dropped
  // otherwise). Motion set points go through commands().want() instead.
  void sendCommand(std::vector<std::uint8_t> payload);
  // STOP or ESTOP ahead of everything else (only while open).
  void sendUrgent(Command command);
  // Moves the command packet due at now_s (if any) to the outgoing queue; tick() does it too.
  void pump(double now_s);
  // The motion slots and the pacing of everything sent after OPEN.
  ArcosCommandScheduler& commands() { return commands_; }
  const ArcosCommandScheduler& commands() const { return commands_; }

  std::vector<std::vector<std::uint8_t>> takeOutgoing();  // complete packets, in order
  std::vector<StandardSip> takeSips();
  std::vector<ArcosEvent> takeEvents();

  ArcosState state() const { return state_; }
  const std::optional<RobotIdentity>& identity() const { return identity_; }
  const ArcosStats& stats() const { return stats_; }

 private:
  void setState(ArcosState state, double now_s, std::string text, bool warning = false);
  void beginSync(double now_s);
  void sendSync(double now_s);
  void queue(std::vector<std::uint8_t> payload);
  bool open() const { return state_ == ArcosState::kOpening || state_ == ArcosState::kConnected; }

  ArcosSessionConfig config_;
  ArcosState state_ = ArcosState::kDisconnected;
  int sync_step_ = 0;  // 0, 1, 2: the SYNC packet awaiting its answer
  int sync_attempts_ = 0;
  double last_sync_sent_s_ = 0.0;
  double step_sent_s_ = 0.0;   // first transmission of the SYNC awaiting its answer
  double sync_retry_s_ = 0.0;  // config's, lengthened to 2.5 measured round trips
  double opened_s_ = 0.0;
  std::optional<RobotIdentity> identity_;
  ArcosStats stats_;
  ArcosCommandScheduler commands_;
  std::vector<std::vector<std::uint8_t>> outgoing_;
  std::vector<StandardSip> sips_;
  std::vector<ArcosEvent> events_;
};

}  // namespace irgs::comms::arcos
