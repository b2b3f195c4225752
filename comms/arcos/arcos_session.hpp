#pragma once
// The client side of an ARCOS connection, pure (no I/O, no clock): the SYNC0/SYNC1/SYNC2
// handshake, OPEN, motor and sonar enabling, the PULSE watchdog and SIP-loss detection. The
// owner feeds it received packets and the time, and writes what takeOutgoing() returns.
//
//   kDisconnected --start()--> kSyncing: SYNC0 until echoed, then SYNC1, then SYNC2 (each
//     resent every sync_retry_s; after max_sync_attempts without progress: CLOSE, start over)
//   SYNC2 reply (name, class, subclass) --> OPEN, ENABLE 1, SONAR 1 --> kOpening
//   first standard SIP --> kConnected; PULSE every pulse_period_s from then on
//   no SIP for sip_timeout_s --> kLost; the handshake starts over on its own (a robot that
//     kept running answers the first SYNC0 with SIPs, so SIPs while syncing trigger CLOSE)
//   stop() --> CLOSE, kDisconnected.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "comms/arcos/arcos_packet.hpp"
#include "comms/arcos/arcos_sip.hpp"

namespace irgs::comms::arcos {

struct ArcosSessionConfig {
  double sync_retry_s = 0.3;
  int max_sync_attempts = 8;
  double pulse_period_s = 0.5;  // ARCOS watchdog defaults to 2 s; pulse well inside it
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

  // Queues a command (sent only while open: kOpening/kConnected; dropped otherwise).
  void sendCommand(std::vector<std::uint8_t> payload);

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

  ArcosSessionConfig config_;
  ArcosState state_ = ArcosState::kDisconnected;
  int sync_step_ = 0;  // 0, 1, 2: the SYNC packet awaiting its answer
  int sync_attempts_ = 0;
  double last_sync_sent_s_ = 0.0;
  double last_pulse_s_ = 0.0;
  double opened_s_ = 0.0;
  std::optional<RobotIdentity> identity_;
  ArcosStats stats_;
  std::vector<std::vector<std::uint8_t>> outgoing_;
  std::vector<StandardSip> sips_;
  std::vector<ArcosEvent> events_;
};

}  // namespace irgs::comms::arcos
