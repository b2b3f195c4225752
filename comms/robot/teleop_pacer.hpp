#pragma once
// When LinkedRobot sends MANUAL_CONTROL, pure (no I/O, no clock: the time is passed in).
//
//  * A changed command goes out at once, unless the previous MANUAL_CONTROL left less than
//    min_interval_s ago: then it goes when that interval is over, and only the newest of the
//    commands wanted meanwhile (coalescing). A caller may call want() every millisecond: the
//    robot never gets more than one MANUAL_CONTROL per min_interval_s.
//  * A non-zero command is repeated every repeat_period_s (10 Hz): the firmware stops the
//    motors when MANUAL_CONTROL pauses for teleop_timeout (0.3 s; docs/protocol.md), so a
//    ground station that dies leaves a robot that stops within that timeout.
//  * A zero command goes once (the firmware ends teleop on it); nothing is sent before the
//    first non-zero command.
// min_interval_s defaults to 55 ms: at most 18.2 MANUAL_CONTROL/s, issue 24's cap of 20/s with
// a tenth in hand so that arrival jitter on the link never shows the robot 21 in a second.

#include <cstdint>
#include <optional>

namespace irgs::comms {

// The MANUAL_CONTROL axes LinkedRobot uses (manualControlFor): x forward, r yaw (clockwise).
struct TeleopAxes {
  std::int16_t x = 0;
  std::int16_t r = 0;
  bool zero() const { return x == 0 && r == 0; }
  friend bool operator==(const TeleopAxes&, const TeleopAxes&) = default;
};

struct TeleopPacerConfig {
  double repeat_period_s = 0.1;   // non-zero commands are repeated this often
  double min_interval_s = 0.055;  // never two MANUAL_CONTROLs closer than this
};

struct TeleopPacerStats {
  std::uint64_t sent = 0;
  std::uint64_t repeats = 0;    // unchanged non-zero commands re-sent as keep-alive
  std::uint64_t coalesced = 0;  // wanted commands replaced before they went out
};

class TeleopPacer {
 public:
  // Throws std::invalid_argument unless 0 < min_interval_s <= repeat_period_s.
  explicit TeleopPacer(TeleopPacerConfig config = {});

  void want(const TeleopAxes& axes);
  // The axes to send at now_s, if any are due (at most one MANUAL_CONTROL per min_interval_s).
  std::optional<TeleopAxes> next(double now_s);

  // The robot no longer holds a teleop command (a behaviour replaced it, the link went down):
  // nothing is pending or repeated, and nothing is sent to say so.
  void cancel();

  const TeleopAxes& wanted() const { return wanted_; }
  const TeleopPacerStats& stats() const { return stats_; }

 private:
  TeleopPacerConfig config_;
  TeleopAxes wanted_;
  std::optional<TeleopAxes> sent_;  // the last sent, empty before the first
  bool pending_ = false;            // wanted_ differs from what went out last
  double last_sent_s_ = -1e300;
  TeleopPacerStats stats_;
};

}  // namespace irgs::comms
