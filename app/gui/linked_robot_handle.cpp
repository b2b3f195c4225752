#include "app/gui/linked_robot_handle.hpp"

#include <algorithm>
#include <iterator>
#include <stdexcept>

namespace irgs::gui {
namespace {

// A robot-clock step backwards by more than this is a reboot (the clock restarted at zero).
constexpr double kRestartJump_s = 0.5;
// The spacing given to the first sample after a reboot on the rebased clock.
constexpr double kRestartStep_s = 0.05;

double spanRate(const std::deque<double>& times) {
  if (times.size() < 2 || times.back() <= times.front())
    return 0.0;
  return static_cast<double>(times.size() - 1) / (times.back() - times.front());
}

}  // namespace

comms::MessageSamplerConfig guiMessageSampling() {
  comms::MessageSamplerConfig config;
  config.max_rate_hz = 25.0;
  return config;
}

LinkedRobotHandle::LinkedRobotHandle(std::shared_ptr<comms::IoThread> io,
                                     std::unique_ptr<comms::LinkedRobot> robot, std::string url)
    : io_(std::move(io)), robot_(std::move(robot)), url_(std::move(url)) {
  if (!io_ || !robot_)
    throw std::invalid_argument("LinkedRobotHandle needs an io thread and a robot");
}

LinkedRobotHandle::~LinkedRobotHandle() {
  robot_.reset();  // closes the link while the io thread still runs
}

std::vector<TelemetrySample> LinkedRobotHandle::update(double wall_elapsed_s) {
  return rebase(robot_->update(wall_elapsed_s));
}

std::vector<TelemetrySample> LinkedRobotHandle::rebase(std::vector<TelemetrySample> samples) {
  for (TelemetrySample& sample : samples) {
    const double robot_time_s = sample.time_s;
    if (!have_time_) {
      have_time_ = true;
      last_time_s_ = 0.0;
    } else if (robot_time_s < last_robot_time_s_ - kRestartJump_s) {
      last_time_s_ += kRestartStep_s;  // rebooted: keep our clock going
      sample_times_s_.clear();
      sonar_times_s_.clear();
      sonar_counts_.clear();
    } else {
      last_time_s_ += std::max(0.0, robot_time_s - last_robot_time_s_);
    }
    last_robot_time_s_ = robot_time_s;
    sample.time_s = last_time_s_;

    ++samples_;
    sample_times_s_.push_back(robot_time_s);
    if (!sample.sonar.empty()) {
      sonar_times_s_.push_back(robot_time_s);
      sonar_counts_.emplace_back(robot_time_s, sample.sonar.size());
      sonar_readings_ += sample.sonar.size();
    }
    const double oldest_s = robot_time_s - kRateWindow_s;
    while (!sample_times_s_.empty() && sample_times_s_.front() < oldest_s)
      sample_times_s_.pop_front();
    while (!sonar_times_s_.empty() && sonar_times_s_.front() < oldest_s)
      sonar_times_s_.pop_front();
    while (!sonar_counts_.empty() && sonar_counts_.front().first < oldest_s)
      sonar_counts_.pop_front();
  }
  return samples;
}

std::vector<comms::MessageSample> LinkedRobotHandle::takeMessages() {
  std::vector<comms::MessageSample> messages = robot_->takeMessages();
  if (!have_time_) {
    // No sample yet, so no offset: they wait (the first sample comes within the assembler's
    // hold time; a robot that sends no odometry keeps only the newest kMaxEarlyMessages).
    early_messages_.insert(early_messages_.end(), std::make_move_iterator(messages.begin()),
                           std::make_move_iterator(messages.end()));
    if (early_messages_.size() > kMaxEarlyMessages)
      early_messages_.erase(early_messages_.begin(),
                            early_messages_.end() - static_cast<std::ptrdiff_t>(kMaxEarlyMessages));
    return {};
  }
  if (!early_messages_.empty()) {
    messages.insert(messages.begin(), std::make_move_iterator(early_messages_.begin()),
                    std::make_move_iterator(early_messages_.end()));
    early_messages_.clear();
  }
  // Samples advance last_time_s_ by the robot clock's steps: this is the offset of the clocks.
  const double offset_s = last_time_s_ - last_robot_time_s_;
  std::erase_if(messages, [&](comms::MessageSample& m) {
    if (m.robot_time_s < last_robot_time_s_ - kRestartJump_s)
      return true;  // the robot rebooted and no sample told us the new offset yet
    m.robot_time_s = std::max(0.0, m.robot_time_s + offset_s);
    return false;
  });
  return messages;
}

TelemetryRates LinkedRobotHandle::rates() const {
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

}  // namespace irgs::gui
