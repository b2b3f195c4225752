#pragma once
// Which ARCOS command packet goes out next, and when: the client's rate discipline, pure (no I/O,
// no clock: the caller passes the time and writes what next() returns).
//
// What the Pioneer documentation asks of a client (docs/pioneer.md, "Command rate"):
//  * one command per packet and no acknowledgement: the client notices a missed command in the
//    SIPs and re-issues it (Pioneer 3 Operations Manual, "Client-server communication packet
//    protocols");
//  * "limit client commands to a maximum of one every 3-5 milliseconds or be prepared to recover
//    from lost commands"; how many per second fit depends on the HOST baud rate (Pioneer 2/3
//    Operations Manual, AROS chapter, "Client commands");
//  * at least one command packet every `watchdog` seconds (2 s by default), else the robot
//    stops (AmigoBot/Pioneer manuals, "Keeping the beat - PULSE").
// ARIA's ArRobot meets them by "state reflection": a motion command is sent when it changes and
// re-sent every 500 ms; PULSE when no motion command is in effect (ARIA docs/overview.dox).
//
// This scheduler does the same under a hard cap:
//  * Two motion slots hold the latest wanted command: translational (VEL or MOVE) and rotational
//    (RVEL, HEAD or DHEAD). want() replaces a value not yet sent (the newest wins); an unchanged
//    repeatable value (VEL, RVEL, HEAD: sending it again changes nothing) is not sent again. MOVE
//    and DHEAD are relative, so each want() of them is a new request.
//  * One-shot commands (ENABLE, SONAR, SETO, ...) go once, in order, before slot changes.
//    Urgent ones (STOP, ESTOP) go before everything and are not held by the token bucket; they
//    leave the robot's set points at zero, so the slots become VEL 0 / RVEL 0 (sent).
//  * Keep-alive: a slot holding a repeatable command is re-sent when it was not sent for
//    refresh_s (a lost command is recovered that way); when nothing at all was sent for
//    keepalive_s, the oldest repeatable slot is re-sent, or PULSE when there is none.
//  * The cap: at most max_packets in any window_s (10 in 1.1 s: issue 24's 10 packets/s with a
//    tenth in hand, so arrival jitter on the link never shows the robot 11 in a second); a token
//    bucket of `burst` packets refilled at max_packets / window_s spreads them (a VEL + RVEL pair
//    goes 20 ms apart, then one packet per 110 ms under a continuous stream of changes); and two
//    packets are at least min_gap_s apart and twice the previous packet's time on the wire at
//    `baud`, so commands never take more than half of the link's byte budget.

#include <array>
#include <cstdint>
#include <deque>
#include <optional>
#include <vector>

#include "comms/arcos/arcos_commands.hpp"

namespace irgs::comms::arcos {

enum class MotionSlot : std::uint8_t { kTranslational = 0, kRotational = 1 };

// A motion command with its int argument (mm, mm/s, degrees or deg/s as ARCOS defines them).
struct SlotCommand {
  Command command = Command::kVel;
  int argument = 0;
  friend bool operator==(const SlotCommand&, const SlotCommand&) = default;
};

// VEL, MOVE -> translational; RVEL, HEAD, DHEAD -> rotational; nullopt for any other command.
std::optional<MotionSlot> slotOf(Command command);
// Sending the command again with the same argument changes nothing on the robot (VEL, RVEL, HEAD).
bool isRepeatable(Command command);

struct ArcosCommandSchedulerConfig {
  int max_packets = 10;       // hard cap: packets in any window_s
  double window_s = 1.1;      // (10 per 1.1 s: <= 10/s with room for arrival jitter)
  int burst = 2;              // token bucket size
  double min_gap_s = 0.02;    // between any two packets (the manuals ask for >= 3-5 ms)
  std::uint32_t baud = 9600;  // the link's baud: a gap of 2x the previous packet's wire time
  double keepalive_s = 0.5;   // nothing sent this long: refresh a slot or PULSE (watchdog 2 s)
  double refresh_s = 1.0;     // a repeatable slot value is re-sent at least this often
};

struct ArcosSchedulerStats {
  std::uint64_t packets = 0;    // handed out by next()
  std::uint64_t bytes = 0;      // their size, framed
  std::uint64_t changes = 0;    // slot values sent because they changed
  std::uint64_t coalesced = 0;  // wanted values replaced (or wanted back) before they went out
  std::uint64_t one_shots = 0;
  std::uint64_t urgent = 0;
  std::uint64_t refreshes = 0;  // repeatable slot values sent again (keep-alive, recovery)
  std::uint64_t pulses = 0;
};

class ArcosCommandScheduler {
 public:
  // Throws std::invalid_argument for a config without a positive cap, window, gap or baud.
  explicit ArcosCommandScheduler(ArcosCommandSchedulerConfig config = {});

  // The newest wanted command of its slot. Throws std::invalid_argument for a command that is
  // not a motion command (slotOf) or an argument outside +-32767.
  void want(const SlotCommand& command);
  // A one-shot command payload (commandPayload), sent once after the urgent ones. Throws
  // std::invalid_argument for an empty payload or one longer than kMaxPayload.
  void sendOnce(std::vector<std::uint8_t> payload);
  // STOP or ESTOP (anything else: std::invalid_argument). A STOP while the set points are
  // already zero and a STOP already went (or is queued) is not sent again.
  void sendUrgent(Command command);

  // The framed packet to write at now_s, if one is due and the cap allows it. Call it at least
  // every min_gap_s (the owner's tick) and after want()/sendOnce()/sendUrgent().
  std::optional<std::vector<std::uint8_t>> next(double now_s);

  // Seconds until the gap after the last packet lets another one go (0 when it does): for a
  // packet sent outside the scheduler, like the CLOSE of a shutdown.
  double gapLeft(double now_s) const;

  // A new connection: forgets the slots, the queues and the send history.
  void reset();

  // The newest value of a slot: wanted and not yet sent, else the last sent; empty before any.
  std::optional<SlotCommand> wanted(MotionSlot slot) const;
  bool idle() const;  // nothing waiting to go out (keep-alives aside)
  const ArcosSchedulerStats& stats() const { return stats_; }
  const ArcosCommandSchedulerConfig& config() const { return config_; }

 private:
  struct Slot {
    std::optional<SlotCommand> sent;     // what the robot should hold
    std::optional<SlotCommand> pending;  // wanted, not yet sent
    std::uint64_t pending_order = 0;     // lower: waiting longer
    double last_sent_s = -1e300;
  };

  double gapAfterLast() const;
  bool capAllows(double now_s) const;  // gap and window (every packet obeys them)
  void refill(double now_s);
  std::vector<std::uint8_t> issue(std::vector<std::uint8_t> payload, double now_s, bool bucket);
  std::optional<std::vector<std::uint8_t>> nextSlotChange(double now_s);
  std::optional<std::vector<std::uint8_t>> nextKeepAlive(double now_s);
  std::vector<std::uint8_t> sendSlot(Slot& slot, const SlotCommand& command, double now_s);

  ArcosCommandSchedulerConfig config_;
  std::array<Slot, 2> slots_{};
  std::deque<std::vector<std::uint8_t>> urgent_;
  std::deque<std::vector<std::uint8_t>> one_shots_;
  bool stop_in_effect_ = false;  // a STOP went (or is queued) and no motion command since
  std::uint64_t order_ = 0;
  double tokens_ = 0.0;
  double refilled_s_ = 0.0;
  bool started_ = false;         // refilled_s_ and started_s_ are valid
  double started_s_ = 0.0;       // the first next(): the keep-alive counts from there
  std::deque<double> recent_s_;  // send times within window_s, oldest first
  double last_sent_s_ = -1e300;
  std::size_t last_bytes_ = 0;
  ArcosSchedulerStats stats_;
};

}  // namespace irgs::comms::arcos
