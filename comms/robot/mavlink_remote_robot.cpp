#include "comms/robot/mavlink_remote_robot.hpp"

#include <iterator>
#include <stdexcept>
#include <utility>

namespace irgs::comms {

MavlinkRemoteRobot::MavlinkRemoteRobot(std::shared_ptr<IoThread> io,
                                       std::unique_ptr<LinkedRobot> robot, std::string url)
    : io_(std::move(io)), robot_(std::move(robot)), url_(std::move(url)) {
  if (!io_ || !robot_)
    throw std::invalid_argument("MavlinkRemoteRobot needs an io thread and a robot");
}

MavlinkRemoteRobot::~MavlinkRemoteRobot() {
  robot_.reset();  // closes the link while the io thread still runs
}

std::vector<TelemetrySample> MavlinkRemoteRobot::update(double wall_elapsed_s) {
  return rebase(robot_->update(wall_elapsed_s));
}

std::vector<TelemetrySample> MavlinkRemoteRobot::finish() {
  return rebase(robot_->finish());
}

std::vector<TelemetrySample> MavlinkRemoteRobot::rebase(std::vector<TelemetrySample> samples) {
  for (TelemetrySample& sample : samples) {
    const double robot_time_s = sample.time_s;
    sample.time_s = clock_.sampleTime(robot_time_s);
    if (clock_.restarted())
      rates_.restart();
    rates_.add(robot_time_s, sample.sonar.size());
  }
  return samples;
}

bool MavlinkRemoteRobot::supports(motion::PrimitiveKind kind) const {
  return robot_->motionControl()->supports(kind);
}

void MavlinkRemoteRobot::start(const motion::Primitive& primitive) {
  robot_->motionControl()->start(primitive);
}

void MavlinkRemoteRobot::cancel() {
  robot_->motionControl()->cancel();
}

std::vector<motion::MotionReport> MavlinkRemoteRobot::takeReports() {
  // LinkedRobot hands a report out only after the samples up to its time, so the clock offset
  // is known; a report stamped after a reboot no sample has shown yet takes the newest time.
  std::vector<motion::MotionReport> reports = robot_->motionControl()->takeReports();
  for (motion::MotionReport& r : reports)
    r.time_s = clock_.otherTime(r.time_s).value_or(clock_.lastTime_s());
  return reports;
}

std::vector<MessageSample> MavlinkRemoteRobot::takeMessages() {
  std::vector<MessageSample> messages = robot_->takeMessages();
  if (!clock_.started()) {
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
  std::erase_if(messages, [&](MessageSample& m) {
    const std::optional<double> time_s = clock_.otherTime(m.robot_time_s);
    if (!time_s)
      return true;  // the robot rebooted and no sample told us the new offset yet
    m.robot_time_s = *time_s;
    return false;
  });
  return messages;
}

void MavlinkRemoteRobot::requestConfirmedStop() {
  robot_->drive({});
  if (stop_sent_)
    return;
  stop_sent_ = true;
  robot_->sendBehaviour({.kind = RobotBehaviourKind::kStop},
                        [answer = stop_answer_](const CommandResult& r) {
                          answer->accepted = r.outcome == CommandOutcome::kAccepted;
                          answer->answered = true;
                        });
}

std::optional<bool> MavlinkRemoteRobot::stopConfirmed() const {
  if (!stop_answer_->answered)
    return std::nullopt;
  return stop_answer_->accepted.load();
}

}  // namespace irgs::comms
