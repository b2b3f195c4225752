#include "comms/robot/telemetry_messages.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/geometry/types.hpp"

namespace irgs::comms {

namespace mav = mavlink;

std::uint32_t bootMs(double t_s) {
  return static_cast<std::uint32_t>(std::llround(std::max(0.0, t_s) * 1000.0));
}

std::uint64_t bootUs(double t_s) {
  return static_cast<std::uint64_t>(std::llround(std::max(0.0, t_s) * 1e6));
}

std::uint16_t toCentimetres(double metres) {
  return static_cast<std::uint16_t>(std::clamp(std::lround(metres * 100.0), 0L, 65534L));
}

std::uint16_t toMillimetres(double metres) {
  return static_cast<std::uint16_t>(std::clamp(std::lround(metres * 1000.0), 0L, 65534L));
}

std::int32_t wireCounts(std::int64_t counts) {
  return static_cast<std::int32_t>(std::clamp<std::int64_t>(
      counts, std::numeric_limits<std::int32_t>::min(), std::numeric_limits<std::int32_t>::max()));
}

mav::IrgsMouseCounts mouseCountsMessage(double time_s, const MouseReading& mouse,
                                        MouseStatus right_status, MouseStatus left_status) {
  mav::IrgsMouseCounts m;
  m.time_usec = bootUs(time_s);
  m.right_x = wireCounts(mouse.right.dx);
  m.right_y = wireCounts(mouse.right.dy);
  m.left_x = wireCounts(mouse.left.dx);
  m.left_y = wireCounts(mouse.left.dy);
  // MouseStatus and IRGS_MOUSE_STATUS share their values (tracking 0, saturated 1, lifted 2).
  m.right_status = static_cast<std::uint8_t>(right_status);
  m.left_status = static_cast<std::uint8_t>(left_status);
  return m;
}

mav::IrgsCasterEncoders casterEncodersMessage(double time_s, const CasterEncoders& c) {
  mav::IrgsCasterEncoders m;
  m.time_usec = bootUs(time_s);
  for (std::size_t i = 0; i < 3; ++i) {
    m.drive[i] = wireCounts(c.drive_ticks[i]);
    m.steering[i] = wireCounts(c.steering_ticks[i]);
  }
  if (c.residual_periods > 0) {
    m.residual_sum = c.residual_sum_rad;
    m.residual_periods = static_cast<std::uint32_t>(
        std::min<std::int64_t>(c.residual_periods, std::numeric_limits<std::uint32_t>::max()));
    m.flags = static_cast<std::uint8_t>(mav::IrgsCasterFlags::kResidualValid);
  }
  return m;
}

mav::IrgsPose2d pose2dMessage(const TelemetrySample& sample) {
  const Pose2& p = sample.odometry_pose;
  mav::IrgsPose2d pose;
  pose.time_boot_ms = bootMs(sample.time_s);
  pose.x = static_cast<float>(p.x);
  pose.y = static_cast<float>(p.y);
  pose.theta = static_cast<float>(wrapAngle(p.theta));
  pose.v = static_cast<float>(sample.measured_velocity.linear_mps);
  pose.omega = static_cast<float>(sample.measured_velocity.angular_radps);
  return pose;
}

mav::IrgsEncoderTicks encoderTicksMessage(const TelemetrySample& sample) {
  mav::IrgsEncoderTicks ticks;
  ticks.time_usec = bootUs(sample.time_s);
  ticks.left_ticks = sample.left_ticks;
  ticks.right_ticks = sample.right_ticks;
  return ticks;
}

mav::IrgsContact contactMessage(const TelemetrySample& sample, const RobotProfile& profile) {
  mav::IrgsContact c;
  c.time_boot_ms = bootMs(sample.time_s);
  c.bumpers = sample.bumpers;
  const auto& proximity = sample.proximity_m;
  c.proximity_count =
      static_cast<std::uint8_t>(std::min<std::size_t>(proximity.size(), c.proximity.size()));
  const auto& specs = profile.proximity;
  for (std::size_t i = 0; i < c.proximity_count; ++i) {
    const bool nothing = i < specs.size() && proximity[i] >= specs[i].max_range_m - 1e-9;
    c.proximity[i] =
        nothing ? std::numeric_limits<std::uint16_t>::max() : toMillimetres(proximity[i]);
  }
  return c;
}

mav::IrgsSonarScan sonarScanMessage(double newest_reading_s,
                                    std::span<const SonarReading> latest_by_sensor,
                                    std::uint16_t fired) {
  mav::IrgsSonarScan scan;
  scan.time_boot_ms = bootMs(newest_reading_s);
  scan.count =
      static_cast<std::uint8_t>(std::min<std::size_t>(latest_by_sensor.size(), scan.range.size()));
  for (std::size_t i = 0; i < scan.count; ++i) {
    scan.range[i] = latest_by_sensor[i].echo ? toMillimetres(latest_by_sensor[i].range_m)
                                             : std::numeric_limits<std::uint16_t>::max();
  }
  scan.fired = fired;
  return scan;
}

mav::DistanceSensor distanceSensorMessage(double time_s, std::size_t index, const SonarSpec& spec,
                                          const SonarReading& reading) {
  mav::DistanceSensor ds;
  ds.time_boot_ms = bootMs(time_s);
  ds.min_distance = toCentimetres(spec.min_range_m);
  ds.max_distance = toCentimetres(spec.max_range_m);
  ds.current_distance = reading.echo ? toCentimetres(reading.range_m)
                                     : static_cast<std::uint16_t>(ds.max_distance + 1);
  ds.type = static_cast<std::uint8_t>(mav::MavDistanceSensor::kUltrasound);
  ds.id = static_cast<std::uint8_t>(index);
  // MAVLink sensor yaw rotations count clockwise in 45 degree steps; our heading is CCW.
  const double cw_deg = -radToDeg(spec.mount.theta);
  const double steps = std::round(cw_deg / 45.0);
  if (std::abs(cw_deg - steps * 45.0) > 1.0) {
    ds.orientation = static_cast<std::uint8_t>(mav::MavSensorOrientation::kCustom);
  } else {
    const long yaw_index = ((static_cast<long>(steps) % 8) + 8) % 8;  // 0 = kNone .. 7 = kYaw315
    ds.orientation = static_cast<std::uint8_t>(yaw_index);
  }
  ds.covariance = std::numeric_limits<std::uint8_t>::max();  // unknown
  ds.horizontal_fov = static_cast<float>(spec.beam_width_rad);
  ds.vertical_fov = static_cast<float>(spec.beam_width_rad);
  return ds;
}

mav::ScaledImu gyroImuMessage(const TelemetrySample& sample) {
  auto to_int16 = [](double value) {
    return static_cast<std::int16_t>(std::clamp(std::lround(value), -32767L, 32767L));
  };
  mav::ScaledImu imu;
  imu.time_boot_ms = bootMs(sample.time_s);
  imu.zacc = -1000;  // mG: gravity, z down
  if (sample.gyro) {
    imu.zgyro = to_int16(-sample.gyro->rate_radps * 1000.0);
    const std::int16_t cdeg = to_int16(sample.gyro->temperature_c * 100.0);
    imu.temperature = cdeg == 0 ? std::int16_t{1} : cdeg;
  }
  return imu;
}

}  // namespace irgs::comms
