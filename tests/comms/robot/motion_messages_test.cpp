// The motion primitives on the wire (comms/robot/motion_messages.hpp): every spec field of every
// kind survives encode -> frame bytes -> decode, the waypoint list's centimetre grid and range,
// the refusal of values outside an enum, the frame sizes docs/protocol.md quotes.

#include "comms/robot/motion_messages.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "comms/mavlink/frame_decoder.hpp"
#include "comms/mavlink/frame_encoder.hpp"

namespace irgs::comms {
namespace {

namespace mav = mavlink;

// Through the real encoder and decoder, as the bytes travel.
template <class M>
M overTheWire(const M& message, std::size_t* frame_bytes = nullptr) {
  mav::FrameEncoder encoder(255, 190);
  const mav::EncodedFrame frame = encoder.encode(message);
  if (frame_bytes != nullptr)
    *frame_bytes = frame.size;
  mav::FrameDecoder decoder;
  const mav::DecodeResult r = decoder.feed(frame.view());
  EXPECT_EQ(r.frames.size(), 1u);
  return r.frames.empty() ? M{} : r.frames[0].as<M>().value_or(M{});
}

motion::Primitive roundTrip(const motion::Primitive& p) {
  const EncodedPrimitive e = encodePrimitive(p, 1);
  EXPECT_TRUE(e.error.empty()) << e.error;
  DecodedPrimitive d;
  if (e.command) {
    EXPECT_EQ(e.command->target_system, 1);
    d = decodePrimitiveCommand(overTheWire(*e.command)).value_or(DecodedPrimitive{});
  } else if (e.waypoints) {
    EXPECT_EQ(e.waypoints->target_system, 1);
    d = decodeWaypoints(overTheWire(*e.waypoints));
  }
  EXPECT_TRUE(d.id_valid);
  EXPECT_TRUE(d.error.empty()) << d.error;
  EXPECT_EQ(d.id, p.id);
  EXPECT_EQ(d.kind, motion::kindOf(p.spec));
  return d.primitive.value_or(motion::Primitive{});
}

TEST(MotionMessages, TurnDriveAndFollowWallKeepEveryFieldAndTheId) {
  // Values a float holds exactly, so the comparison can be exact.
  const motion::TurnSpec turn{-1.25, true, 0.25, 0.5};
  EXPECT_EQ(std::get<motion::TurnSpec>(roundTrip({7, turn}).spec), turn);
  const motion::DriveSpec drive{-0.75, 0.125, false, 0.5};
  EXPECT_EQ(std::get<motion::DriveSpec>(roundTrip({65535, drive}).spec), drive);
  const motion::DriveSpec walled{2.5, 0.0, true, 0.0};
  EXPECT_EQ(std::get<motion::DriveSpec>(roundTrip({1, walled}).spec), walled);
  const motion::FollowWallSpec follow{false, 0.375, 0.25, 12.5, true, true, 0.5};
  EXPECT_EQ(std::get<motion::FollowWallSpec>(roundTrip({300, follow}).spec), follow);
  const motion::FollowWallSpec plain{true, 0.3125, 0.0, 0.0, false, false, 0.0};
  EXPECT_EQ(std::get<motion::FollowWallSpec>(roundTrip({2, plain}).spec), plain);
}

TEST(MotionMessages, LegacyCommandsWithoutIdOrFlagsStillDecode) {
  // A generic ground station's MOVE_DISTANCE: distance and speed only.
  mav::CommandLong move;
  move.command = static_cast<std::uint16_t>(mav::MavCmd::kIrgsMoveDistance);
  move.param1 = 0.5f;
  move.param2 = 0.2f;
  const auto d = decodePrimitiveCommand(move);
  ASSERT_TRUE(d && d->primitive);
  EXPECT_EQ(d->id, 0);  // the robot picks one
  const auto& spec = std::get<motion::DriveSpec>(d->primitive->spec);
  EXPECT_FALSE(spec.stop_at_wall);  // as MOVE_DISTANCE always drove
  EXPECT_EQ(spec.clearance_m, 0.0);
  mav::CommandLong other;
  other.command = static_cast<std::uint16_t>(mav::MavCmd::kIrgsStop);
  EXPECT_FALSE(decodePrimitiveCommand(other));
}

TEST(MotionMessages, SegmentsAndPathTravelOnACentimetreGridFromTheFirstWaypoint) {
  motion::SegmentsSpec s;
  s.append(Vec2(12.3456, -7.891));
  s.append(Vec2(13.0, -7.0));
  s.append(Vec2(-100.004, 200.0));
  s.speed_mps = 0.25;
  s.quantum_rad = 0.25;
  s.clearance_m = 0.5;
  s.stop_at_wall = false;
  const auto back = std::get<motion::SegmentsSpec>(roundTrip({9, s}).spec);
  ASSERT_EQ(back.count, 3);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_NEAR(back.points[i].x(), s.points[i].x(), 0.005 + 1e-6) << i;
    EXPECT_NEAR(back.points[i].y(), s.points[i].y(), 0.005 + 1e-6) << i;
  }
  EXPECT_NEAR(back.points[0].x(), 12.3456, 1e-5);  // the origin itself: float precision
  EXPECT_EQ(back.speed_mps, 0.25);
  EXPECT_EQ(back.quantum_rad, 0.25);
  EXPECT_EQ(back.clearance_m, 0.5);
  EXPECT_FALSE(back.stop_at_wall);

  motion::FollowPathSpec path;
  for (int i = 0; i < 32; ++i)
    path.append(Vec2(0.1 * i, std::sin(0.3 * i)));
  path.speed_mps = 0.125;
  const auto path_back = std::get<motion::FollowPathSpec>(roundTrip({10, path}).spec);
  ASSERT_EQ(path_back.count, 32);
  for (std::size_t i = 0; i < 32; ++i)
    EXPECT_NEAR((path_back.points[i] - path.points[i]).norm(), 0.0, 0.0071) << i;
  EXPECT_EQ(path_back.speed_mps, 0.125);
}

TEST(MotionMessages, WaypointFramesCostOnlyTheirOwnPoints) {
  motion::SegmentsSpec s;
  for (int i = 0; i < 32; ++i)
    s.append(Vec2(1.0 + 0.5 * i, 2.0 - 0.25 * i));
  std::size_t full = 0;
  overTheWire(*encodePrimitive({1, s}).waypoints, &full);
  EXPECT_EQ(full, 12u + 27u + 4u * 32u);  // 167 bytes: 174 ms at 9600 baud
  motion::SegmentsSpec short_list;
  for (int i = 0; i < 4; ++i)  // the last y negative: its high byte is no trailing zero
    short_list.append(Vec2(1.0 + 0.5 * i, 2.0 - 0.5 * i));
  std::size_t small = 0;
  overTheWire(*encodePrimitive({1, short_list}).waypoints, &small);
  EXPECT_EQ(small, 12u + 27u + 4u * 4u);
}

TEST(MotionMessages, WaypointsBeyondTheInt16RangeOrNotFiniteCannotBeSent) {
  motion::SegmentsSpec far;
  far.append(Vec2(0.0, 0.0));
  far.append(Vec2(327.0, 0.0));
  EXPECT_TRUE(encodePrimitive({1, far}).error.empty());
  far.append(Vec2(0.0, -327.7));
  const EncodedPrimitive e = encodePrimitive({1, far});
  EXPECT_FALSE(e.waypoints);
  EXPECT_NE(e.error.find("waypoint 2"), std::string::npos) << e.error;
  motion::FollowPathSpec nan;
  nan.append(Vec2(std::numeric_limits<double>::quiet_NaN(), 0.0));
  EXPECT_FALSE(encodePrimitive({1, nan}).error.empty());
}

TEST(MotionMessages, ValuesOutsideTheirEnumsAreErrorsWithTheIdKept) {
  mav::CommandLong follow = *encodePrimitive({4, motion::FollowWallSpec{}}).command;
  follow.param2 = 2.0f;  // no such side
  auto d = decodePrimitiveCommand(follow);
  ASSERT_TRUE(d);
  EXPECT_TRUE(d->id_valid);
  EXPECT_EQ(d->id, 4);
  EXPECT_FALSE(d->primitive);
  EXPECT_NE(d->error.find("side"), std::string::npos);

  mav::CommandLong turn = *encodePrimitive({5, motion::TurnSpec{}}).command;
  turn.param4 = 2.0f;  // STOP_AT_WALL means nothing to a turn
  EXPECT_FALSE(decodePrimitiveCommand(turn)->primitive);
  turn.param4 = 0.5f;
  EXPECT_FALSE(decodePrimitiveCommand(turn)->primitive);
  turn.param4 = 0.0f;
  turn.param7 = 1.5f;  // not an id
  EXPECT_FALSE(decodePrimitiveCommand(turn)->id_valid);
  turn.param7 = 70000.0f;
  EXPECT_FALSE(decodePrimitiveCommand(turn)->id_valid);

  mav::IrgsWaypoints w = *encodePrimitive({6, motion::SegmentsSpec{}}).waypoints;
  w.count = 33;
  EXPECT_FALSE(decodeWaypoints(w).primitive);
  w.count = 1;
  w.kind = static_cast<std::uint8_t>(mav::IrgsPrimitiveKind::kTurn);
  EXPECT_FALSE(decodeWaypoints(w).primitive);
  w.kind = static_cast<std::uint8_t>(mav::IrgsPrimitiveKind::kFollowPath);
  w.flags = static_cast<std::uint8_t>(mav::IrgsMotionFlags::kStopAtWall);  // path: no wall stop
  EXPECT_FALSE(decodeWaypoints(w).primitive);
  EXPECT_EQ(decodeWaypoints(w).id, 6);
}

TEST(MotionMessages, ReportsKeepTheirFieldsOnTheRobotClock) {
  motion::MotionReport r;
  r.id = 4242;
  r.kind = motion::ReportKind::kTurningPoint;
  r.reason = motion::Reason::kNone;
  r.time_s = 12.34;
  r.pose = {1.5, -2.25, 0.5};
  r.distance_m = 3.75;
  r.index = 17;
  std::size_t bytes = 0;
  const auto back = motionReportFrom(overTheWire(motionReportMessage(r), &bytes));
  ASSERT_TRUE(back);
  EXPECT_EQ(*back, r);
  EXPECT_LE(bytes, 38u);
  mav::IrgsMotionReport unknown = motionReportMessage(r);
  unknown.kind = 11;
  EXPECT_FALSE(motionReportFrom(unknown));
  unknown.kind = 0;
  unknown.reason = 8;
  EXPECT_FALSE(motionReportFrom(unknown));
}

TEST(MotionMessages, StopCarriesTheIdInParamSeven) {
  const mav::CommandLong stop = stopPrimitiveCommand(77, 1);
  EXPECT_EQ(stop.command, static_cast<std::uint16_t>(mav::MavCmd::kIrgsStop));
  EXPECT_EQ(stop.param7, 77.0f);
  EXPECT_EQ(stop.target_system, 1);
}

}  // namespace
}  // namespace irgs::comms
