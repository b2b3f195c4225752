#pragma once
// Turns a robot's telemetry samples into the MAVLink frames a robot running the IRGS firmware's
// compact streams would send for them (docs/protocol.md): a HEARTBEAT once a second of robot
// time, and per sample IRGS_POSE_2D, IRGS_ENCODER_TICKS (IRGS_CASTER_ENCODERS for a three-caster
// robot), IRGS_MOUSE_COUNTS when it has floor sensors, IRGS_SONAR_SCAN when sonars fired
// (DISTANCE_SENSOR for robots with more sonars than the scan holds), IRGS_CONTACT when it
// changed or every 0.1 s, SCALED_IMU when the sample has a gyro. TelemetryAssembler decodes
// them back into the same samples (the pose in float, sonar ranges in mm, the gyro in mrad/s).
//
// Why: the ground station records a simulator session as the bytes such a robot would have
// sent, so that a simulator recording replays and re-runs through the same link path as a
// recording of a real robot (docs/gui.md, "Recording and replay"). Pure: no clock, no I/O.

#include <cstdint>
#include <optional>
#include <vector>

#include "comms/mavlink/frame_encoder.hpp"
#include "core/robot/robot_profile.hpp"
#include "core/robot/telemetry.hpp"

namespace irgs::comms {

class TelemetryFrameWriter {
 public:
  static constexpr double kHeartbeatPeriod_s = 1.0;
  static constexpr double kContactPeriod_s = 0.1;

  explicit TelemetryFrameWriter(RobotProfile profile, std::uint8_t system_id = 1,
                                std::uint8_t component_id = 1);

  // The frames for `sample`, appended to `out`. A sample older than the previous one starts
  // over (a new robot: heartbeat first, as after a reboot).
  void write(const TelemetrySample& sample, std::vector<std::uint8_t>& out);
  std::vector<std::uint8_t> write(const TelemetrySample& sample);

  const RobotProfile& profile() const { return profile_; }

 private:
  template <class M>
  void append(const M& message, std::vector<std::uint8_t>& out);

  RobotProfile profile_;
  mavlink::FrameEncoder encoder_;
  std::optional<double> last_time_s_;
  std::optional<double> last_heartbeat_s_;
  std::optional<double> last_contact_s_;
  std::uint32_t last_bumpers_ = 0;
  std::vector<double> last_proximity_m_;
  std::vector<SonarReading> latest_sonar_;  // per sonar, for the scan
};

}  // namespace irgs::comms
