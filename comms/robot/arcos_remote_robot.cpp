#include "comms/robot/arcos_remote_robot.hpp"

#include <cmath>
#include <stdexcept>
#include <utility>

namespace irgs::comms {

ArcosRemoteRobot::ArcosRemoteRobot(std::unique_ptr<ArcosRobot> robot, std::string url)
    : robot_(std::move(robot)), url_(std::move(url)) {
  if (!robot_)
    throw std::invalid_argument("ArcosRemoteRobot needs a robot");
}

std::vector<TelemetrySample> ArcosRemoteRobot::update(double wall_elapsed_s) {
  std::vector<TelemetrySample> samples = robot_->update(wall_elapsed_s);
  if (stop_sent_ && !at_rest_) {
    for (const TelemetrySample& s : samples) {
      if (std::abs(s.measured_velocity.linear_mps) < kRestSpeed_mps &&
          std::abs(s.measured_velocity.angular_radps) < degToRad(kRestTurnRate_degps))
        at_rest_ = true;
    }
  }
  return samples;
}

TelemetryRates ArcosRemoteRobot::telemetryRates() const {
  const ArcosTelemetryRates arcos = robot_->telemetryRates();
  TelemetryRates rates;
  rates.odometry_hz = arcos.sample_hz;
  rates.sonar_hz = arcos.sonar_hz;
  rates.sonar_readings_per_s = arcos.sonar_readings_per_s;
  rates.samples = arcos.samples;
  rates.sonar_readings = arcos.sonar_readings;
  return rates;
}

void ArcosRemoteRobot::requestConfirmedStop() {
  if (stop_sent_)
    return;
  stop_sent_ = true;
  robot_->stop();
}

std::optional<bool> ArcosRemoteRobot::stopConfirmed() const {
  return at_rest_ ? std::optional<bool>(true) : std::nullopt;
}

}  // namespace irgs::comms
