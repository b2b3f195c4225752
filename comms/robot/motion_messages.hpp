#pragma once
// The robot-side motion primitives (core/motion/primitive.hpp) on the wire, both ways
// (docs/protocol.md section 18). Pure conversions: the ground station (MavlinkMotionClient)
// encodes, the virtual firmware (app/robot/firmware_motion.hpp) decodes.
//
//  * TURN, DRIVE and FOLLOW_WALL travel as COMMAND_LONG MAV_CMD_IRGS_TURN_ANGLE /
//    MOVE_DISTANCE / FOLLOW_WALL (every spec field in params 1-6, the primitive id in param 7),
//    so any ground station can send them with the command protocol's ack and retries.
//  * SEGMENTS and FOLLOW_PATH travel as one IRGS_WAYPOINTS frame: up to 32 waypoints as int16
//    centimetres from an origin, 167 bytes at most (a mission upload of 32 items costs about
//    2 kB and 32 round trips, docs/protocol.md section 18).
//  * Reports travel as IRGS_MOTION_REPORT; a stop of one primitive is MAV_CMD_IRGS_STOP with
//    its id in param 7.
// Frames: the robot's odometry frame (FLU: x forward at start, y left, theta counter-clockwise),
// SI units, as the vocabulary.

#include <cstdint>
#include <optional>
#include <string>

#include "comms/mavlink/messages.hpp"
#include "core/motion/primitive.hpp"

namespace irgs::comms {

inline constexpr double kWaypointUnit_m = 0.01;  // IRGS_WAYPOINTS.points: centimetres
// The command parameter that carries the primitive id (all IRGS motion commands and STOP).
inline constexpr int kPrimitiveIdParam = 7;

// Exactly one of command / waypoints, or an error saying why the spec cannot be sent (a
// waypoint too far from the first for int16 centimetres, a non-finite waypoint).
struct EncodedPrimitive {
  std::optional<mavlink::CommandLong> command;
  std::optional<mavlink::IrgsWaypoints> waypoints;
  std::string error;
};
EncodedPrimitive encodePrimitive(const motion::Primitive& primitive,
                                 std::uint8_t target_system = 0);

// A decoded start. `id_valid` false: param 7 is not an integer in 0..65535 (nothing can be
// reported for it). Otherwise `primitive` is set (its id may be 0: the robot picks one), or
// `error` names the field that cannot be a spec (a side or flag value outside its enum, more
// than 32 waypoints). Values the executor itself checks (NaN, negative speeds) pass through.
struct DecodedPrimitive {
  bool id_valid = false;
  std::uint16_t id = 0;
  motion::PrimitiveKind kind = motion::PrimitiveKind::kTurn;
  std::optional<motion::Primitive> primitive;
  std::string error;
};
// nullopt when `command` is not one of the motion commands (MOVE_DISTANCE, TURN_ANGLE,
// FOLLOW_WALL).
std::optional<DecodedPrimitive> decodePrimitiveCommand(const mavlink::CommandLong& command);
DecodedPrimitive decodeWaypoints(const mavlink::IrgsWaypoints& message);

// MAV_CMD_IRGS_STOP of the primitive `id` (0: everything, teleop included).
mavlink::CommandLong stopPrimitiveCommand(std::uint16_t id, std::uint8_t target_system = 0);

mavlink::IrgsMotionReport motionReportMessage(const motion::MotionReport& report);
// nullopt for a kind or reason value this build does not know.
std::optional<motion::MotionReport> motionReportFrom(const mavlink::IrgsMotionReport& message);

// Wire enum values (IRGS_PRIMITIVE_KIND, IRGS_MOTION_REPORT_KIND, IRGS_MOTION_REASON) to the
// vocabulary; nullopt for unknown values.
std::optional<motion::PrimitiveKind> primitiveKindFrom(std::uint8_t wire);
std::optional<motion::ReportKind> reportKindFrom(std::uint8_t wire);
std::optional<motion::Reason> reasonFrom(std::uint8_t wire);

}  // namespace irgs::comms
