#include "comms/robot/motion_messages.hpp"

#include <cmath>
#include <limits>
#include <variant>

#include "comms/robot/telemetry_messages.hpp"

namespace irgs::comms {

namespace mav = mavlink;

namespace {

// The wire enums are the vocabulary's, value for value (resources/mavlink/irgs.xml).
template <class A, class B>
constexpr bool same(A a, B b) {
  return static_cast<int>(a) == static_cast<int>(b);
}
static_assert(same(mav::IrgsPrimitiveKind::kTurn, motion::PrimitiveKind::kTurn) &&
              same(mav::IrgsPrimitiveKind::kDrive, motion::PrimitiveKind::kDrive) &&
              same(mav::IrgsPrimitiveKind::kFollowWall, motion::PrimitiveKind::kFollowWall) &&
              same(mav::IrgsPrimitiveKind::kSegments, motion::PrimitiveKind::kSegments) &&
              same(mav::IrgsPrimitiveKind::kFollowPath, motion::PrimitiveKind::kFollowPath));
static_assert(same(mav::IrgsMotionReportKind::kStarted, motion::ReportKind::kStarted) &&
              same(mav::IrgsMotionReportKind::kRefused, motion::ReportKind::kRefused) &&
              same(mav::IrgsMotionReportKind::kTurningPoint, motion::ReportKind::kTurningPoint) &&
              same(mav::IrgsMotionReportKind::kDistanceMark, motion::ReportKind::kDistanceMark) &&
              same(mav::IrgsMotionReportKind::kMode, motion::ReportKind::kMode) &&
              same(mav::IrgsMotionReportKind::kContact, motion::ReportKind::kContact) &&
              same(mav::IrgsMotionReportKind::kWallLost, motion::ReportKind::kWallLost) &&
              same(mav::IrgsMotionReportKind::kFrontWall, motion::ReportKind::kFrontWall) &&
              same(mav::IrgsMotionReportKind::kDone, motion::ReportKind::kDone) &&
              same(mav::IrgsMotionReportKind::kFailed, motion::ReportKind::kFailed) &&
              same(mav::IrgsMotionReportKind::kCancelled, motion::ReportKind::kCancelled));
static_assert(same(mav::IrgsMotionReason::kNone, motion::Reason::kNone) &&
              same(mav::IrgsMotionReason::kInvalid, motion::Reason::kInvalid) &&
              same(mav::IrgsMotionReason::kUnsupported, motion::Reason::kUnsupported) &&
              same(mav::IrgsMotionReason::kBumped, motion::Reason::kBumped) &&
              same(mav::IrgsMotionReason::kBlocked, motion::Reason::kBlocked) &&
              same(mav::IrgsMotionReason::kNoProgress, motion::Reason::kNoProgress) &&
              same(mav::IrgsMotionReason::kSafety, motion::Reason::kSafety) &&
              same(mav::IrgsMotionReason::kNoSensors, motion::Reason::kNoSensors));
// motion::Reason::kNoAnswer is the ground station's own verdict on a start nobody answered
// (MavlinkMotionClient); no robot sends it, so the dialect has no value for it.

constexpr std::uint8_t kTurnAbsolute =
    static_cast<std::uint8_t>(mav::IrgsMotionFlags::kTurnAbsolute);
constexpr std::uint8_t kStopAtWall = static_cast<std::uint8_t>(mav::IrgsMotionFlags::kStopAtWall);
constexpr std::uint8_t kStopWhenLost =
    static_cast<std::uint8_t>(mav::IrgsMotionFlags::kStopWhenLost);
constexpr std::uint8_t kStopAtFrontWall =
    static_cast<std::uint8_t>(mav::IrgsMotionFlags::kStopAtFrontWall);
constexpr float kSideLeft = static_cast<float>(mav::IrgsWallSide::kLeft);
constexpr float kSideRight = static_cast<float>(mav::IrgsWallSide::kRight);

template <class T>
constexpr std::uint16_t cmd(T value) {
  return static_cast<std::uint16_t>(value);
}

// A float parameter that must hold a whole number in [0, max].
std::optional<std::uint32_t> wholeParam(float value, std::uint32_t max) {
  if (!std::isfinite(value) || value < 0.0f || value > static_cast<float>(max) ||
      value != std::floor(value))
    return std::nullopt;
  return static_cast<std::uint32_t>(value);
}

// Flags limited to `allowed`; nullopt for a non-integer or a bit outside it.
std::optional<std::uint8_t> flagsParam(float value, std::uint8_t allowed) {
  const auto flags = wholeParam(value, 255);
  if (!flags || (*flags & ~static_cast<std::uint32_t>(allowed)) != 0)
    return std::nullopt;
  return static_cast<std::uint8_t>(*flags);
}

EncodedPrimitive encodeCommand(std::uint16_t command, std::uint16_t id,
                               std::uint8_t target_system) {
  EncodedPrimitive out;
  out.command.emplace();
  out.command->target_system = target_system;
  out.command->command = command;
  out.command->param7 = static_cast<float>(id);
  return out;
}

// Points as int16 centimetres from the first one (exactly representable as a float origin).
EncodedPrimitive encodeWaypoints(const std::array<Vec2, motion::kMaxWaypoints>& points,
                                 std::uint8_t count, motion::PrimitiveKind kind, std::uint16_t id,
                                 std::uint8_t target_system) {
  EncodedPrimitive out;
  mav::IrgsWaypoints m;
  m.id = id;
  m.target_system = target_system;
  m.kind = static_cast<std::uint8_t>(kind);
  m.count = count;
  if (count > 0) {
    m.origin_x = static_cast<float>(points[0].x());
    m.origin_y = static_cast<float>(points[0].y());
  }
  for (std::size_t i = 0; i < count && i < motion::kMaxWaypoints; ++i) {
    const double dx = (points[i].x() - static_cast<double>(m.origin_x)) / kWaypointUnit_m;
    const double dy = (points[i].y() - static_cast<double>(m.origin_y)) / kWaypointUnit_m;
    constexpr double kLimit = std::numeric_limits<std::int16_t>::max();
    if (!std::isfinite(dx) || !std::isfinite(dy) || std::abs(dx) > kLimit ||
        std::abs(dy) > kLimit) {
      out.error = "waypoint " + std::to_string(i) +
                  " is not finite or more than 327 m from the first (IRGS_WAYPOINTS: int16 cm)";
      return out;
    }
    m.points[2 * i] = static_cast<std::int16_t>(std::lround(dx));
    m.points[2 * i + 1] = static_cast<std::int16_t>(std::lround(dy));
  }
  out.waypoints = m;
  return out;
}

// One encoder per kind (std::visit picks it).
EncodedPrimitive encodeSpec(const motion::TurnSpec& s, std::uint16_t id, std::uint8_t target) {
  EncodedPrimitive e = encodeCommand(cmd(mav::MavCmd::kIrgsTurnAngle), id, target);
  e.command->param1 = static_cast<float>(s.angle_rad);
  e.command->param2 = static_cast<float>(s.rate_radps);
  e.command->param3 = static_cast<float>(s.quantum_rad);
  e.command->param4 = s.absolute ? kTurnAbsolute : 0.0f;
  return e;
}

EncodedPrimitive encodeSpec(const motion::DriveSpec& s, std::uint16_t id, std::uint8_t target) {
  EncodedPrimitive e = encodeCommand(cmd(mav::MavCmd::kIrgsMoveDistance), id, target);
  e.command->param1 = static_cast<float>(s.distance_m);
  e.command->param2 = static_cast<float>(s.speed_mps);
  e.command->param3 = static_cast<float>(s.clearance_m);
  e.command->param4 = s.stop_at_wall ? kStopAtWall : 0.0f;
  return e;
}

EncodedPrimitive encodeSpec(const motion::FollowWallSpec& s, std::uint16_t id,
                            std::uint8_t target) {
  EncodedPrimitive e = encodeCommand(cmd(mav::MavCmd::kIrgsFollowWall), id, target);
  e.command->param1 = static_cast<float>(s.distance_m);
  e.command->param2 = s.wall_on_left ? kSideLeft : kSideRight;
  e.command->param3 = static_cast<float>(s.speed_mps);
  e.command->param4 = static_cast<float>(s.travel_limit_m);
  e.command->param5 = static_cast<float>(s.report_every_m);
  e.command->param6 = static_cast<float>((s.stop_when_lost ? kStopWhenLost : 0) |
                                         (s.stop_at_front_wall ? kStopAtFrontWall : 0));
  return e;
}

EncodedPrimitive encodeSpec(const motion::SegmentsSpec& s, std::uint16_t id, std::uint8_t target) {
  EncodedPrimitive e =
      encodeWaypoints(s.points, s.count, motion::PrimitiveKind::kSegments, id, target);
  if (e.waypoints) {
    e.waypoints->speed = static_cast<float>(s.speed_mps);
    e.waypoints->quantum = static_cast<float>(s.quantum_rad);
    e.waypoints->clearance = static_cast<float>(s.clearance_m);
    e.waypoints->flags = s.stop_at_wall ? kStopAtWall : 0;
  }
  return e;
}

EncodedPrimitive encodeSpec(const motion::FollowPathSpec& s, std::uint16_t id,
                            std::uint8_t target) {
  EncodedPrimitive e =
      encodeWaypoints(s.points, s.count, motion::PrimitiveKind::kFollowPath, id, target);
  if (e.waypoints)
    e.waypoints->speed = static_cast<float>(s.speed_mps);
  return e;
}

}  // namespace

EncodedPrimitive encodePrimitive(const motion::Primitive& primitive, std::uint8_t target_system) {
  return std::visit([&](const auto& spec) { return encodeSpec(spec, primitive.id, target_system); },
                    primitive.spec);
}

std::optional<DecodedPrimitive> decodePrimitiveCommand(const mav::CommandLong& c) {
  DecodedPrimitive d;
  switch (static_cast<mav::MavCmd>(c.command)) {
    case mav::MavCmd::kIrgsTurnAngle:
      d.kind = motion::PrimitiveKind::kTurn;
      break;
    case mav::MavCmd::kIrgsMoveDistance:
      d.kind = motion::PrimitiveKind::kDrive;
      break;
    case mav::MavCmd::kIrgsFollowWall:
      d.kind = motion::PrimitiveKind::kFollowWall;
      break;
    default:
      return std::nullopt;
  }
  const auto id = wholeParam(c.param7, std::numeric_limits<std::uint16_t>::max());
  if (!id) {
    d.error = "param 7 (id) is not an integer in 0..65535";
    return d;
  }
  d.id_valid = true;
  d.id = static_cast<std::uint16_t>(*id);
  motion::Primitive p;
  p.id = d.id;
  switch (d.kind) {
    case motion::PrimitiveKind::kTurn: {
      const auto flags = flagsParam(c.param4, kTurnAbsolute);
      if (!flags) {
        d.error = "param 4 (flags) is not TURN_ABSOLUTE or 0";
        return d;
      }
      motion::TurnSpec s;
      s.angle_rad = c.param1;
      s.rate_radps = c.param2;
      s.quantum_rad = c.param3;
      s.absolute = (*flags & kTurnAbsolute) != 0;
      p.spec = s;
      break;
    }
    case motion::PrimitiveKind::kDrive: {
      const auto flags = flagsParam(c.param4, kStopAtWall);
      if (!flags) {
        d.error = "param 4 (flags) is not STOP_AT_WALL or 0";
        return d;
      }
      motion::DriveSpec s;
      s.distance_m = c.param1;
      s.speed_mps = c.param2;
      s.clearance_m = c.param3;
      s.stop_at_wall = (*flags & kStopAtWall) != 0;
      p.spec = s;
      break;
    }
    default: {  // follow wall
      const auto flags = flagsParam(c.param6, kStopWhenLost | kStopAtFrontWall);
      if (c.param2 != kSideLeft && c.param2 != kSideRight) {
        d.error = "param 2 (side) is not IRGS_WALL_SIDE";
        return d;
      }
      if (!flags) {
        d.error = "param 6 (flags) is not STOP_WHEN_LOST, STOP_AT_FRONT_WALL or 0";
        return d;
      }
      motion::FollowWallSpec s;
      s.distance_m = c.param1;
      s.wall_on_left = c.param2 == kSideLeft;
      s.speed_mps = c.param3;
      s.travel_limit_m = c.param4;
      s.report_every_m = c.param5;
      s.stop_when_lost = (*flags & kStopWhenLost) != 0;
      s.stop_at_front_wall = (*flags & kStopAtFrontWall) != 0;
      p.spec = s;
      break;
    }
  }
  d.primitive = p;
  return d;
}

DecodedPrimitive decodeWaypoints(const mav::IrgsWaypoints& m) {
  DecodedPrimitive d;
  d.id_valid = true;
  d.id = m.id;
  const auto kind = primitiveKindFrom(m.kind);
  if (kind != motion::PrimitiveKind::kSegments && kind != motion::PrimitiveKind::kFollowPath) {
    d.kind = motion::PrimitiveKind::kSegments;
    d.error = "kind is not SEGMENTS or FOLLOW_PATH";
    return d;
  }
  d.kind = *kind;
  if (m.count > motion::kMaxWaypoints) {
    d.error = "more than 32 waypoints";
    return d;
  }
  const bool segments = d.kind == motion::PrimitiveKind::kSegments;
  if ((m.flags & ~(segments ? kStopAtWall : 0)) != 0) {
    d.error = segments ? "flags are not STOP_AT_WALL or 0" : "flags are not 0";
    return d;
  }
  auto fill = [&](auto& spec) {
    for (std::size_t i = 0; i < m.count; ++i)
      spec.append(Vec2(static_cast<double>(m.origin_x) + m.points[2 * i] * kWaypointUnit_m,
                       static_cast<double>(m.origin_y) + m.points[2 * i + 1] * kWaypointUnit_m));
    spec.speed_mps = m.speed;
  };
  motion::Primitive p;
  p.id = m.id;
  if (segments) {
    motion::SegmentsSpec s;
    fill(s);
    s.quantum_rad = m.quantum;
    s.clearance_m = m.clearance;
    s.stop_at_wall = (m.flags & kStopAtWall) != 0;
    p.spec = s;
  } else {
    motion::FollowPathSpec s;
    fill(s);
    p.spec = s;
  }
  d.primitive = p;
  return d;
}

mav::CommandLong stopPrimitiveCommand(std::uint16_t id, std::uint8_t target_system) {
  mav::CommandLong c;
  c.target_system = target_system;
  c.command = cmd(mav::MavCmd::kIrgsStop);
  c.param7 = static_cast<float>(id);
  return c;
}

mav::IrgsMotionReport motionReportMessage(const motion::MotionReport& r) {
  mav::IrgsMotionReport m;
  m.time_boot_ms = bootMs(r.time_s);
  m.x = static_cast<float>(r.pose.x);
  m.y = static_cast<float>(r.pose.y);
  m.theta = static_cast<float>(r.pose.theta);
  m.distance = static_cast<float>(r.distance_m);
  m.id = r.id;
  m.index = r.index;
  m.kind = static_cast<std::uint8_t>(r.kind);
  m.reason = static_cast<std::uint8_t>(r.reason);
  return m;
}

std::optional<motion::MotionReport> motionReportFrom(const mav::IrgsMotionReport& m) {
  const auto kind = reportKindFrom(m.kind);
  const auto reason = reasonFrom(m.reason);
  if (!kind || !reason)
    return std::nullopt;
  motion::MotionReport r;
  r.id = m.id;
  r.kind = *kind;
  r.reason = *reason;
  r.time_s = static_cast<double>(m.time_boot_ms) * 1e-3;  // as TelemetrySample::time_s
  r.pose = {m.x, m.y, m.theta};
  r.distance_m = m.distance;
  r.index = m.index;
  return r;
}

std::optional<motion::PrimitiveKind> primitiveKindFrom(std::uint8_t wire) {
  if (wire > static_cast<std::uint8_t>(motion::PrimitiveKind::kFollowPath))
    return std::nullopt;
  return static_cast<motion::PrimitiveKind>(wire);
}

std::optional<motion::ReportKind> reportKindFrom(std::uint8_t wire) {
  if (wire > static_cast<std::uint8_t>(motion::ReportKind::kCancelled))
    return std::nullopt;
  return static_cast<motion::ReportKind>(wire);
}

std::optional<motion::Reason> reasonFrom(std::uint8_t wire) {
  if (wire > static_cast<std::uint8_t>(motion::Reason::kNoSensors))
    return std::nullopt;
  return static_cast<motion::Reason>(wire);
}

}  // namespace irgs::comms
