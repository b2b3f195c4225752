#pragma once
// What a ground station receives from a robot behind a link, counted since connecting and
// measured on the robot's own clock (sample time stamps) over the last kWindow_s, so the rates
// are the robot's and not those of the GUI's drain: one sample per odometry time stamp, with the
// sonar readings of that time stamp.

#include <cstddef>
#include <cstdint>
#include <deque>
#include <utility>

namespace irgs::comms {

struct TelemetryRates {
  static constexpr double kWindow_s = 3.0;
  double odometry_hz = 0.0;  // samples per second (one per odometry time stamp)
  double sonar_hz = 0.0;     // samples carrying at least one sonar reading, per second
  double sonar_readings_per_s = 0.0;
  std::uint64_t samples = 0;  // since connecting
  std::uint64_t sonar_readings = 0;
};

// Counts samples and measures their rates over the last kWindow_s of the robot's clock.
class TelemetryRateMeter {
 public:
  // A sample stamped `robot_time_s` with `sonar_readings` readings (times non-decreasing until
  // restart()).
  void add(double robot_time_s, std::size_t sonar_readings);
  // The robot's clock started over (it rebooted): the windows empty, the totals stay.
  void restart();
  TelemetryRates rates() const;

 private:
  std::deque<double> sample_times_s_;
  std::deque<double> sonar_times_s_;
  std::deque<std::pair<double, std::size_t>> sonar_counts_;
  std::uint64_t samples_ = 0;
  std::uint64_t sonar_readings_ = 0;
};

}  // namespace irgs::comms
