#pragma once
// Counts packets by their arrival time on the robot's clock: the total, the most that arrived
// within any window (1 s: "packets per second on the wire", what issue 24 caps) and the mean
// rate. irgs-robot keeps one for the ARCOS command packets and one for MANUAL_CONTROL and
// prints them on exit, for the end-to-end tests that check the client's rate discipline.

#include <cstdint>
#include <deque>
#include <optional>
#include <string>

namespace irgs::app {

class ArrivalRateMeter {
 public:
  // Throws std::invalid_argument for a window that is not > 0.
  explicit ArrivalRateMeter(double window_s = 1.0);

  // Arrival times must not decrease (several packets may share one).
  void record(double arrival_s);

  std::uint64_t count() const { return count_; }
  // The most arrivals within any half-open window [t, t + window_s).
  std::uint32_t peak() const { return peak_; }
  // count / (last - first arrival); 0 with fewer than two arrivals or no time between them.
  double meanPerSecond() const;
  // "523 in 61.2 s (8.5/s), peak 10 in 1 s"
  std::string summary() const;

 private:
  double window_s_;
  std::deque<double> recent_;  // arrivals within window_s of the newest
  std::uint64_t count_ = 0;
  std::uint32_t peak_ = 0;
  std::optional<double> first_s_;
  double last_s_ = 0.0;
};

}  // namespace irgs::app
