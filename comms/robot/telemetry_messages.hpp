#pragma once
// A robot's telemetry sample as the IRGS dialect's messages, the encoding the virtual robot
// firmware (app/robot) streams and TelemetryAssembler decodes (docs/protocol.md): pose in our
// frame (IRGS_POSE_2D), cumulative encoder, floor-sensor and caster counts, contacts, the sonar
// scan, the gyro. Pure conversions;
// which message goes out when is the sender's business.

#include <cstdint>
#include <span>

#include "comms/mavlink/messages.hpp"
#include "core/robot/robot_profile.hpp"
#include "core/robot/telemetry.hpp"

namespace irgs::comms {

// Robot time [s] as the messages' time since boot (negative times clamp to 0).
std::uint32_t bootMs(double t_s);
std::uint64_t bootUs(double t_s);
// A distance as the messages' unsigned fields, clamped to 0..65534 (65535 means "nothing").
std::uint16_t toCentimetres(double metres);
std::uint16_t toMillimetres(double metres);

mavlink::IrgsPose2d pose2dMessage(const TelemetrySample& sample);
mavlink::IrgsEncoderTicks encoderTicksMessage(const TelemetrySample& sample);
// Cumulative counts as the messages' int32, clamped rather than wrapped beyond it (68 km of
// travel at 800 cpi, 2.1e9 counts of a caster encoder).
std::int32_t wireCounts(std::int64_t counts);
// Both floor sensors' cumulative counts, each with the state given (a sender reporting less
// often than it reads passes the worst state since its previous report).
mavlink::IrgsMouseCounts mouseCountsMessage(double time_s, const MouseReading& mouse,
                                            MouseStatus right_status, MouseStatus left_status);
// The six caster counts and, when the robot counted any, its own J+ residual sum.
mavlink::IrgsCasterEncoders casterEncodersMessage(double time_s, const CasterEncoders& casters);
// Bumper bits and IR proximity (UINT16_MAX where the sensor sees nothing within its range).
mavlink::IrgsContact contactMessage(const TelemetrySample& sample, const RobotProfile& profile);
// The latest reading of each sonar (index = sensor), `fired` = those fresh since the last scan,
// stamped with the newest reading's time. Sensors beyond the message's 12 are left out.
mavlink::IrgsSonarScan sonarScanMessage(double newest_reading_s,
                                        std::span<const SonarReading> latest_by_sensor,
                                        std::uint16_t fired);

// One sonar reading as DISTANCE_SENSOR: id = the sonar's index, no echo = max_distance + 1
// ("out of range, nothing seen"), orientation = the mount heading as MAV_SENSOR_ROTATION_YAW_*
// (which counts clockwise; CUSTOM when it is not a multiple of 45 degrees).
mavlink::DistanceSensor distanceSensorMessage(double time_s, std::size_t index,
                                              const SonarSpec& spec, const SonarReading& reading);

// SCALED_IMU carrying only the sample's gyro (body FRD: zgyro = -rate in mrad/s, temperature in
// cdegC, 0 C sent as 0.01 C since 0 means "none"), the accelerometer reading -1 g on z as at
// rest: for senders that have no accelerometer model (the simulator's recorded stream).
mavlink::ScaledImu gyroImuMessage(const TelemetrySample& sample);

}  // namespace irgs::comms
