#pragma once
// The mixed telemetry stream the decoder benchmark parses: per 50 ms tick one HEARTBEAT, eight
// DISTANCE_SENSOR (one per thesis-robot sonar), one ODOMETRY and one SCALED_IMU, as irgs-robot
// would send them from system 1, component 1. Values vary like a robot driving a circle in a
// room (seeded), so trailing-zero truncation trims payloads as it would on the wire.

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "comms/mavlink/frame_encoder.hpp"
#include "comms/mavlink/messages.hpp"

namespace irgs::bench {

struct StreamStats {
  std::size_t ticks = 0;
  std::size_t frames = 0;
};

inline std::vector<std::uint8_t> mixedTelemetryStream(std::size_t ticks, std::uint32_t seed,
                                                      StreamStats* stats = nullptr) {
  namespace mav = comms::mavlink;
  mav::FrameEncoder encoder(1, 1);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> noise(-1.0, 1.0);
  std::vector<std::uint8_t> out;
  std::size_t frames = 0;
  auto append = [&](const auto& message) {
    const auto frame = encoder.encode(message);
    out.insert(out.end(), frame.view().begin(), frame.view().end());
    ++frames;
  };
  for (std::size_t k = 0; k < ticks; ++k) {
    const double t = 0.05 * static_cast<double>(k);
    const auto ms = static_cast<std::uint32_t>(std::lround(t * 1000.0));
    const double theta = 0.1 * t;  // 0.3 m/s on a 3 m circle
    mav::Heartbeat hb;
    hb.type = static_cast<std::uint8_t>(mav::MavType::kGroundRover);
    hb.base_mode = 0x81;
    hb.custom_mode = 1;
    hb.system_status = static_cast<std::uint8_t>(mav::MavState::kActive);
    append(hb);
    for (std::uint8_t s = 0; s < 8; ++s) {
      mav::DistanceSensor ds;
      ds.time_boot_ms = ms;
      ds.min_distance = 10;
      ds.max_distance = 300;
      ds.current_distance = static_cast<std::uint16_t>(150.0 + 120.0 * noise(rng));
      ds.type = static_cast<std::uint8_t>(mav::MavDistanceSensor::kUltrasound);
      ds.id = s;
      ds.orientation = s;
      ds.covariance = 255;
      ds.horizontal_fov = 0.436f;
      ds.vertical_fov = 0.436f;
      append(ds);
    }
    mav::Odometry od;
    od.time_usec = static_cast<std::uint64_t>(t * 1e6);
    od.frame_id = static_cast<std::uint8_t>(mav::MavFrame::kLocalNed);
    od.child_frame_id = static_cast<std::uint8_t>(mav::MavFrame::kBodyFrd);
    od.x = static_cast<float>(3.0 * std::sin(theta));
    od.y = static_cast<float>(-3.0 * (1.0 - std::cos(theta)));
    od.q = {static_cast<float>(std::cos(-0.5 * theta)), 0.0f, 0.0f,
            static_cast<float>(std::sin(-0.5 * theta))};
    od.vx = static_cast<float>(0.3 + 0.01 * noise(rng));
    od.yawspeed = -0.1f;
    od.pose_covariance[0] = std::numeric_limits<float>::quiet_NaN();
    od.velocity_covariance[0] = std::numeric_limits<float>::quiet_NaN();
    od.estimator_type = static_cast<std::uint8_t>(mav::MavEstimatorType::kNaive);
    append(od);
    mav::ScaledImu imu;
    imu.time_boot_ms = ms;
    imu.xacc = static_cast<std::int16_t>(20.0 * noise(rng));
    imu.yacc = static_cast<std::int16_t>(30.0 + 20.0 * noise(rng));
    imu.zacc = static_cast<std::int16_t>(-1000.0 + 20.0 * noise(rng));
    imu.zgyro = static_cast<std::int16_t>(-100.0 + 5.0 * noise(rng));
    append(imu);
  }
  if (stats != nullptr) {
    stats->ticks = ticks;
    stats->frames = frames;
  }
  return out;
}

}  // namespace irgs::bench
