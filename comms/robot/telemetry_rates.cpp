#include "comms/robot/telemetry_rates.hpp"

namespace irgs::comms {
namespace {

double spanRate(const std::deque<double>& times) {
  if (times.size() < 2 || times.back() <= times.front())
    return 0.0;
  return static_cast<double>(times.size() - 1) / (times.back() - times.front());
}

}  // namespace

void TelemetryRateMeter::add(double robot_time_s, std::size_t sonar_readings) {
  ++samples_;
  sample_times_s_.push_back(robot_time_s);
  if (sonar_readings > 0) {
    sonar_times_s_.push_back(robot_time_s);
    sonar_counts_.emplace_back(robot_time_s, sonar_readings);
    sonar_readings_ += sonar_readings;
  }
  const double oldest_s = robot_time_s - TelemetryRates::kWindow_s;
  while (!sample_times_s_.empty() && sample_times_s_.front() < oldest_s)
    sample_times_s_.pop_front();
  while (!sonar_times_s_.empty() && sonar_times_s_.front() < oldest_s)
    sonar_times_s_.pop_front();
  while (!sonar_counts_.empty() && sonar_counts_.front().first < oldest_s)
    sonar_counts_.pop_front();
}

void TelemetryRateMeter::restart() {
  sample_times_s_.clear();
  sonar_times_s_.clear();
  sonar_counts_.clear();
}

TelemetryRates TelemetryRateMeter::rates() const {
  TelemetryRates rates;
  rates.odometry_hz = spanRate(sample_times_s_);
  rates.sonar_hz = spanRate(sonar_times_s_);
  if (sonar_counts_.size() >= 2 && sonar_counts_.back().first > sonar_counts_.front().first) {
    std::size_t readings = 0;
    for (std::size_t i = 1; i < sonar_counts_.size(); ++i)  // the first opens the span
      readings += sonar_counts_[i].second;
    rates.sonar_readings_per_s =
        static_cast<double>(readings) / (sonar_counts_.back().first - sonar_counts_.front().first);
  }
  rates.samples = samples_;
  rates.sonar_readings = sonar_readings_;
  return rates;
}

}  // namespace irgs::comms
