#include "comms/robot/telemetry_frame_writer.hpp"

#include <cmath>
#include <limits>
#include <utility>

#include "comms/mavlink/messages.hpp"
#include "comms/robot/telemetry_messages.hpp"

namespace irgs::comms {

namespace mav = mavlink;

TelemetryFrameWriter::TelemetryFrameWriter(RobotProfile profile, std::uint8_t system_id,
                                           std::uint8_t component_id)
    : profile_(std::move(profile)), encoder_(system_id, component_id) {
  latest_sonar_.resize(profile_.sonars.size());
  for (std::size_t i = 0; i < latest_sonar_.size(); ++i) {
    latest_sonar_[i].sensor = static_cast<int>(i);
    latest_sonar_[i].range_m = profile_.sonars[i].max_range_m;
  }
}

template <class M>
void TelemetryFrameWriter::append(const M& message, std::vector<std::uint8_t>& out) {
  const mav::EncodedFrame frame = encoder_.encode(message);
  const auto bytes = frame.view();
  out.insert(out.end(), bytes.begin(), bytes.end());
}

std::vector<std::uint8_t> TelemetryFrameWriter::write(const TelemetrySample& sample) {
  std::vector<std::uint8_t> out;
  write(sample, out);
  return out;
}

void TelemetryFrameWriter::write(const TelemetrySample& sample, std::vector<std::uint8_t>& out) {
  const double t = sample.time_s;
  if (!std::isfinite(t))
    return;
  if (last_time_s_ && t < *last_time_s_) {  // a new robot or a reset: start over
    last_heartbeat_s_.reset();
    last_contact_s_.reset();
  }
  last_time_s_ = t;

  if (!last_heartbeat_s_ || t - *last_heartbeat_s_ >= kHeartbeatPeriod_s - 1e-9) {
    mav::Heartbeat hb;
    hb.type = static_cast<std::uint8_t>(mav::MavType::kGroundRover);
    hb.autopilot = static_cast<std::uint8_t>(mav::MavAutopilot::kGeneric);
    hb.base_mode = static_cast<std::uint8_t>(mav::MavModeFlag::kCustomModeEnabled) |
                   static_cast<std::uint8_t>(mav::MavModeFlag::kSafetyArmed);
    const bool moving =
        sample.measured_velocity.linear_mps != 0.0 || sample.measured_velocity.angular_radps != 0.0;
    hb.system_status =
        static_cast<std::uint8_t>(moving ? mav::MavState::kActive : mav::MavState::kStandby);
    append(hb, out);
    last_heartbeat_s_ = t;
  }

  // The pose first: the assembler starts a step with it and lets the step's readings join.
  append(pose2dMessage(sample), out);
  if (!sample.casters)  // a three-caster robot has no left/right wheels
    append(encoderTicksMessage(sample), out);
  else
    append(casterEncodersMessage(t, *sample.casters), out);
  if (sample.mouse)  // one report per reading: its own state is the worst since the last
    append(
        mouseCountsMessage(t, *sample.mouse, sample.mouse->right.status, sample.mouse->left.status),
        out);

  if (!sample.sonar.empty()) {
    constexpr std::size_t kScanCapacity = mav::IrgsSonarScan{}.range.size();
    if (profile_.sonars.size() <= kScanCapacity) {
      std::uint16_t fired = 0;
      for (const SonarReading& r : sample.sonar) {
        if (r.sensor < 0 || static_cast<std::size_t>(r.sensor) >= latest_sonar_.size())
          continue;
        latest_sonar_[static_cast<std::size_t>(r.sensor)] = r;
        fired = static_cast<std::uint16_t>(fired | (1u << r.sensor));
      }
      if (fired != 0)
        append(sonarScanMessage(t, latest_sonar_, fired), out);
    } else {
      for (const SonarReading& r : sample.sonar) {
        if (r.sensor < 0 || static_cast<std::size_t>(r.sensor) >= profile_.sonars.size() ||
            r.sensor > std::numeric_limits<std::uint8_t>::max())
          continue;
        const auto index = static_cast<std::size_t>(r.sensor);
        append(distanceSensorMessage(t, index, profile_.sonars[index], r), out);
      }
    }
  }

  const bool has_contacts = !profile_.bumpers.empty() || !profile_.proximity.empty();
  const bool contact_changed =
      sample.bumpers != last_bumpers_ || sample.proximity_m != last_proximity_m_;
  if (has_contacts &&
      (!last_contact_s_ || contact_changed || t - *last_contact_s_ >= kContactPeriod_s - 1e-9)) {
    append(contactMessage(sample, profile_), out);
    last_contact_s_ = t;
    last_bumpers_ = sample.bumpers;
    last_proximity_m_ = sample.proximity_m;
  }

  if (sample.gyro)
    append(gyroImuMessage(sample), out);
}

}  // namespace irgs::comms
