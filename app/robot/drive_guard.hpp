#pragma once
// Who may drive irgs-robot over a listening transport (docs/protocol.md, "Who may drive"). The
// ground station attached to the TCP server or UDP listener keeps the robot while it is active:
// alive by its protocol's own measure (MAVLink: a ground-station heartbeat within the firmware's
// timeout; ARCOS: bytes within the watchdog) or attached less than a grace period ago (it has
// not had time to say hello). A second one meanwhile is refused by the transport
// (comms::PeerPolicy); the guard counts the refusals and words the report for the attached
// ground station and stderr, at most one per report period (a refused ground station that keeps
// reconnecting must not flood the link). Pure: the caller passes the time.

#include <cstdint>
#include <optional>
#include <string>

namespace irgs::app {

class DriveGuard {
 public:
  static constexpr double kDefaultReportPeriod_s = 5.0;

  // Throws std::invalid_argument unless grace_s > 0 and report_period_s >= 0.
  explicit DriveGuard(double grace_s, double report_period_s = kDefaultReportPeriod_s);

  // The transport attached a peer (a TCP client connected).
  void peerAttached(double now_s);
  // Bytes from the attached peer arrived: the first ones after a peer was let go attach the
  // next one (a UDP listener attaches a sender by delivering its datagram).
  void peerBytes(double now_s);
  // Whether the attached peer still holds the robot; `alive` is the protocol's liveness. False
  // lets the newcomer in: the next bytes then attach it.
  bool peerActive(double now_s, bool alive);

  // A peer ("address:port") was refused. Returns the report when one is due now, e.g.
  // "refused client 127.0.0.1:40312 (3 total)" (at most 50 characters: a STATUSTEXT).
  std::optional<std::string> refused(const std::string& peer, double now_s);
  // The report of refusals held back by the rate limit, once it is due (call periodically).
  std::optional<std::string> dueReport(double now_s);
  std::uint64_t refusedTotal() const { return refused_total_; }

 private:
  std::string report(double now_s);

  double grace_s_;
  double report_period_s_;
  double attached_at_s_ = 0.0;
  bool waiting_for_peer_ = true;  // no peer attached, or the last one was let go
  std::uint64_t refused_total_ = 0;
  std::uint64_t reported_total_ = 0;
  std::string last_refused_;
  std::optional<double> next_report_s_;
};

}  // namespace irgs::app
