// FirmwareCore services over the wire (fake ground station, fake clock): parameters,
// MAV_CMD_SET_MESSAGE_INTERVAL, SYS_STATUS, SCALED_IMU, mission upload/download and execution as
// the traveling algorithm, and FOLLOW_WALL through the core wall follower.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "app/robot/firmware_core.hpp"
#include "comms/mavlink/messages.hpp"
#include "tests/app/robot/firmware_test_support.hpp"

namespace irgs::app {
namespace {

namespace mav = comms::mavlink;
using namespace firmware_test;  // NOLINT: the test support vocabulary

constexpr auto kAccepted = static_cast<std::uint8_t>(mav::MavResult::kAccepted);
constexpr auto kDenied = static_cast<std::uint8_t>(mav::MavResult::kDenied);
constexpr auto kUnsupported = static_cast<std::uint8_t>(mav::MavResult::kUnsupported);

std::string name(const mav::ParamValue& v) {
  return paramIdToString(v.param_id);
}

void setParam(Gcs& gcs, const std::string& id, float value) {
  mav::ParamSet set;
  set.target_system = 1;
  set.target_component = 1;
  set.param_id = paramIdField(id);
  set.param_value = value;
  set.param_type = static_cast<std::uint8_t>(mav::MavParamType::kReal32);
  gcs.send(set, gcs.now());
}

std::optional<mav::ParamValue> lastParam(const Gcs& gcs, const std::string& id) {
  std::optional<mav::ParamValue> out;
  for (const auto& v : gcs.all<mav::ParamValue>())
    if (name(v) == id)
      out = v;
  return out;
}

void setInterval(Gcs& gcs, std::uint32_t message_id, float interval_us) {
  mav::CommandLong c;
  c.target_system = 1;
  c.command = static_cast<std::uint16_t>(mav::MavCmd::kSetMessageInterval);
  c.param1 = static_cast<float>(message_id);
  c.param2 = interval_us;
  gcs.send(c, gcs.now());
}

template <class M>
double countPerSecond(const Gcs& gcs, double from, double to) {
  std::size_t n = 0;
  for (const auto& r : gcs.received)
    if (r.t_s > from && r.t_s <= to && r.frame.as<M>())
      ++n;
  return static_cast<double>(n) / (to - from);
}

// ---- Parameters ----------------------------------------------------------------------------

TEST(FirmwareParams, RequestListSendsEveryParameterWithIndexAndCount) {
  FirmwareCore core = makeCore(room(false));
  Gcs gcs(core);
  gcs.run(0.1, true, std::nullopt);
  mav::ParamRequestList list;
  list.target_system = 1;
  gcs.send(list, gcs.now());
  gcs.run(0.2, true, std::nullopt);
  const auto values = gcs.all<mav::ParamValue>();
  ASSERT_EQ(values.size(), ParamTable::size());
  for (std::size_t i = 0; i < values.size(); ++i) {
    EXPECT_EQ(values[i].param_index, i);
    EXPECT_EQ(values[i].param_count, ParamTable::size());
    EXPECT_EQ(values[i].param_type, static_cast<std::uint8_t>(mav::MavParamType::kReal32));
    EXPECT_EQ(name(values[i]), paramSpecs()[i].name);
  }
  EXPECT_FLOAT_EQ(lastParam(gcs, "TELEOP_TIMEOUT")->param_value, 0.3f);
  EXPECT_FLOAT_EQ(lastParam(gcs, "HB_TIMEOUT")->param_value, 1.5f);
  EXPECT_FLOAT_EQ(lastParam(gcs, "SR_POSE")->param_value, 20.0f);
  EXPECT_FLOAT_EQ(lastParam(gcs, "SR_STATUS")->param_value, 1.0f);
  EXPECT_FLOAT_EQ(lastParam(gcs, "MAX_SPEED")->param_value,
                  static_cast<float>(core.simulator().profile().limits.max_speed_mps));
}

TEST(FirmwareParams, RequestReadFindsParametersByNameAndByIndex) {
  FirmwareCore core = makeCore(room(false));
  Gcs gcs(core);
  gcs.run(0.1, true, std::nullopt);
  mav::ParamRequestRead by_name;
  by_name.target_system = 1;
  by_name.param_index = -1;
  by_name.param_id = paramIdField("HB_TIMEOUT");
  gcs.send(by_name, gcs.now());
  mav::ParamRequestRead by_index;
  by_index.target_system = 1;
  by_index.param_index = static_cast<std::int16_t>(ParamId::kTeleopTimeout);
  gcs.send(by_index, gcs.now());
  mav::ParamRequestRead missing;
  missing.target_system = 1;
  missing.param_index = -1;
  missing.param_id = paramIdField("NO_SUCH_PARAM");
  gcs.send(missing, gcs.now());
  gcs.run(0.2, true, std::nullopt);
  const auto values = gcs.all<mav::ParamValue>();
  ASSERT_EQ(values.size(), 2u);
  EXPECT_EQ(name(values[0]), "HB_TIMEOUT");
  EXPECT_EQ(name(values[1]), "TELEOP_TIMEOUT");
  EXPECT_TRUE(gcs.saidSomething("no parameter NO_SUCH_PARAM"));
}

TEST(FirmwareParams, ShorterTeleopTimeoutStopsTheRobotSooner) {
  FirmwareCore core = makeCore(room(false));
  Gcs gcs(core);
  setParam(gcs, "TELEOP_TIMEOUT", 0.1f);
  gcs.run(1.0, true, std::make_pair<std::int16_t, std::int16_t>(1000, 0));
  ASSERT_TRUE(lastParam(gcs, "TELEOP_TIMEOUT"));
  EXPECT_FLOAT_EQ(lastParam(gcs, "TELEOP_TIMEOUT")->param_value, 0.1f);
  EXPECT_NEAR(core.config().teleop_timeout_s, 0.1, 1e-6);
  ASSERT_FALSE(stopped(core));
  const double last_command = 0.91;
  double stop_time = -1.0;
  while (gcs.now() < 2.0 && stop_time < 0.0) {
    gcs.run(gcs.now() + 0.01, true, std::nullopt);
    if (stopped(core))
      stop_time = gcs.now();
  }
  ASSERT_GT(stop_time, 0.0);
  EXPECT_LE(stop_time - last_command, 0.1 + 0.03);
}

TEST(FirmwareParams, OutOfRangeValuesAreRefusedWithTheUnchangedValue) {
  FirmwareCore core = makeCore(room(false));
  Gcs gcs(core);
  gcs.run(0.05, true, std::nullopt);
  setParam(gcs, "TELEOP_TIMEOUT", 1.0f);  // would break "stop within 0.5 s"
  setParam(gcs, "HB_TIMEOUT", std::numeric_limits<float>::quiet_NaN());
  setParam(gcs, "MAX_SPEED", 99.0f);  // beyond the robot profile
  setParam(gcs, "BOGUS", 1.0f);
  gcs.run(0.1, true, std::nullopt);
  const auto values = gcs.all<mav::ParamValue>();
  ASSERT_EQ(values.size(), 3u);  // no answer for an unknown name, a STATUSTEXT instead
  EXPECT_FLOAT_EQ(values[0].param_value, 0.3f);
  EXPECT_FLOAT_EQ(values[1].param_value, 1.5f);
  EXPECT_FLOAT_EQ(values[2].param_value,
                  static_cast<float>(core.simulator().profile().limits.max_speed_mps));
  EXPECT_TRUE(gcs.saidSomething("TELEOP_TIMEOUT: 1 outside"));
  EXPECT_TRUE(gcs.saidSomething("HB_TIMEOUT: value is not a number"));
  EXPECT_TRUE(gcs.saidSomething("no parameter BOGUS"));
  EXPECT_NEAR(core.config().teleop_timeout_s, 0.3, 1e-9);
}

TEST(FirmwareParams, HeartbeatTimeoutParameterTakesEffect) {
  FirmwareCore core = makeCore(room(false));
  Gcs gcs(core);
  gcs.run(0.05, true, std::nullopt);
  setParam(gcs, "HB_TIMEOUT", 0.6f);
  setParam(gcs, "TELEOP_TIMEOUT", 0.45f);
  // Heartbeats stop after the one at 0.01 s; MANUAL_CONTROL keeps coming.
  gcs.run(0.3, false, std::make_pair<std::int16_t, std::int16_t>(500, 0));
  double stop_time = -1.0;
  while (gcs.now() < 2.0 && stop_time < 0.0) {
    gcs.run(gcs.now() + 0.01, false, std::make_pair<std::int16_t, std::int16_t>(500, 0));
    if (stopped(core))
      stop_time = gcs.now();
  }
  ASSERT_GT(stop_time, 0.0);
  EXPECT_NEAR(stop_time, 0.01 + 0.6, 0.03);
  EXPECT_TRUE(gcs.saidSomething("heartbeat lost"));
}

TEST(FirmwareParams, MaxSpeedScalesFullStick) {
  FirmwareCore core = makeCore(room(false));
  Gcs gcs(core);
  gcs.run(0.05, true, std::nullopt);
  setParam(gcs, "MAX_SPEED", 0.1f);
  gcs.run(2.0, true, std::make_pair<std::int16_t, std::int16_t>(1000, 0));
  EXPECT_NEAR(core.simulator().trueVelocity().linear_mps, 0.1, 1e-6);
}

TEST(FirmwareParams, StreamRateParametersChangeTheRates) {
  FirmwareCore core = makeCore(room(false));
  Gcs gcs(core);
  gcs.run(0.05, true, std::nullopt);
  setParam(gcs, "SR_POSE", 5.0f);
  setParam(gcs, "SR_IMU", 0.0f);
  setParam(gcs, "SR_STATUS", 2.0f);
  gcs.run(3.0, true, std::nullopt);
  EXPECT_NEAR(countPerSecond<mav::Odometry>(gcs, 1.0, 3.0), 5.0, 0.5);
  EXPECT_NEAR(countPerSecond<mav::LocalPositionNed>(gcs, 1.0, 3.0), 5.0, 0.5);
  EXPECT_EQ(countPerSecond<mav::ScaledImu>(gcs, 1.0, 3.0), 0.0);
  EXPECT_NEAR(countPerSecond<mav::SysStatus>(gcs, 1.0, 3.0), 2.0, 0.5);
  EXPECT_NEAR(*core.messagePeriod(mav::Odometry::kId), 0.2, 1e-9);
  // Switching the group back on restores the messages the configuration enables.
  setParam(gcs, "SR_IMU", 20.0f);
  gcs.run(5.0, true, std::nullopt);
  EXPECT_NEAR(countPerSecond<mav::ScaledImu>(gcs, 3.5, 5.0), 20.0, 1.0);
}

// ---- SET_MESSAGE_INTERVAL ----------------------------------------------------------------------

TEST(FirmwareStreams, SetMessageIntervalChangesDisablesAndRestoresOneMessage) {
  FirmwareCore core = makeCore(room(false));
  Gcs gcs(core);
  gcs.run(0.05, true, std::nullopt);
  setInterval(gcs, mav::Odometry::kId, 100000.0f);  // 10 Hz
  setInterval(gcs, mav::DistanceSensor::kId, -1.0f);
  gcs.run(2.0, true, std::nullopt);
  EXPECT_NEAR(countPerSecond<mav::Odometry>(gcs, 0.5, 2.0), 10.0, 1.0);
  EXPECT_NEAR(countPerSecond<mav::LocalPositionNed>(gcs, 0.5, 2.0), 20.0, 1.0);  // untouched
  EXPECT_EQ(countPerSecond<mav::DistanceSensor>(gcs, 0.5, 2.0), 0.0);
  setInterval(gcs, mav::Odometry::kId, 0.0f);  // default
  setInterval(gcs, mav::DistanceSensor::kId, 0.0f);
  gcs.run(4.0, true, std::nullopt);
  EXPECT_NEAR(countPerSecond<mav::Odometry>(gcs, 2.5, 4.0), 20.0, 1.0);
  EXPECT_NEAR(countPerSecond<mav::DistanceSensor>(gcs, 2.5, 4.0), 80.0, 8.0);
  const auto acks = acksFor(gcs, mav::MavCmd::kSetMessageInterval);
  ASSERT_EQ(acks.size(), 4u);
  for (const auto& a : acks)
    EXPECT_EQ(a.result, kAccepted);
}

TEST(FirmwareStreams, HeartbeatIntervalIsFixedAndUnknownMessagesAreUnsupported) {
  FirmwareCore core = makeCore(room(false));
  Gcs gcs(core);
  gcs.run(0.05, true, std::nullopt);
  setInterval(gcs, mav::Heartbeat::kId, 5e6f);
  setInterval(gcs, mav::Timesync::kId, 1e5f);
  setInterval(gcs, mav::Odometry::kId, -7.0f);
  setInterval(gcs, mav::Odometry::kId, std::numeric_limits<float>::infinity());
  gcs.run(0.2, true, std::nullopt);
  const auto acks = acksFor(gcs, mav::MavCmd::kSetMessageInterval);
  ASSERT_EQ(acks.size(), 4u);
  EXPECT_EQ(acks[0].result, kDenied);
  EXPECT_EQ(acks[1].result, kUnsupported);
  EXPECT_EQ(acks[2].result, kDenied);
  EXPECT_EQ(acks[3].result, kDenied);
  EXPECT_NEAR(*core.messagePeriod(mav::Odometry::kId), 0.05, 1e-12);
}

TEST(FirmwareStatus, TimesyncRequestsAreAnsweredWithTheRequestMirrored) {
  FirmwareCore core = makeCore(room(false));
  Gcs gcs(core);
  gcs.run(0.5, true, std::nullopt);
  mav::Timesync request;
  request.ts1 = 123456789;
  request.target_system = 1;
  gcs.send(request, gcs.now());
  mav::Timesync reply_to_other = request;
  reply_to_other.tc1 = 42;  // an answer, not a request: ignored
  gcs.send(reply_to_other, gcs.now());
  gcs.run(0.6, true, std::nullopt);
  const auto syncs = gcs.all<mav::Timesync>();
  ASSERT_EQ(syncs.size(), 1u);
  EXPECT_EQ(syncs[0].ts1, 123456789);
  EXPECT_NEAR(static_cast<double>(syncs[0].tc1), 0.5e9, 1e7);
  EXPECT_EQ(syncs[0].target_system, 255);
  EXPECT_EQ(syncs[0].target_component, 190);
}

// ---- SYS_STATUS and SCALED_IMU -----------------------------------------------------------------

TEST(FirmwareStatus, SysStatusAt1HzReportsSensorsBatteryAndReceiveErrors) {
  FirmwareCore core = makeCore(room(false));
  Gcs gcs(core);
  gcs.run(3.0, true, std::make_pair<std::int16_t, std::int16_t>(800, 0));
  EXPECT_NEAR(countPerSecond<mav::SysStatus>(gcs, 1.0, 3.0), 1.0, 0.5);
  const auto first = gcs.all<mav::SysStatus>().back();
  const std::uint32_t expected = 1u | 2u | 32768u | 33554432u | 67108864u;
  EXPECT_EQ(first.onboard_control_sensors_present, expected);
  EXPECT_EQ(first.onboard_control_sensors_health, expected);
  EXPECT_GT(first.voltage_battery, 12000);
  EXPECT_LE(first.voltage_battery, 12600);
  EXPECT_GT(first.current_battery, 25);  // idle 0.25 A plus driving
  EXPECT_GE(first.battery_remaining, 99);
  EXPECT_EQ(first.errors_comm, 0);
  EXPECT_EQ(first.drop_rate_comm, 0);
  EXPECT_LT(core.batteryRemaining(), 1.0);

  // A corrupted frame (one payload bit flipped) and an e-stop: both show in the next report.
  mav::FrameEncoder other(255, 190);
  auto frame = other.encode(mav::Heartbeat{});
  frame.bytes[12] ^= 0x10;
  core.receiveBytes(frame.view(), gcs.now());
  gcs.command(mav::MavCmd::kIrgsEmergencyStop, 1.0f, gcs.now());
  gcs.run(gcs.now() + 1.5, true, std::nullopt);
  const auto after = gcs.all<mav::SysStatus>().back();
  EXPECT_GE(after.errors_comm, 1);
  EXPECT_GT(after.drop_rate_comm, 0);
  EXPECT_EQ(after.onboard_control_sensors_health & 32768u, 0u);  // motors latched off
}

TEST(FirmwareStatus, ScaledImuShowsTheTrueTurnRateAndGravityInFrd) {
  FirmwareCore core = makeCore(room(false));
  Gcs gcs(core);
  // r = -600: counter-clockwise at 0.6 of the maximum turn rate.
  gcs.run(3.0, true, std::make_pair<std::int16_t, std::int16_t>(0, -600));
  const double omega = 0.6 * core.simulator().profile().limits.max_turn_rate_radps;
  ASSERT_NEAR(core.simulator().trueVelocity().angular_radps, omega, 1e-6);
  EXPECT_NEAR(countPerSecond<mav::ScaledImu>(gcs, 1.0, 3.0), 10.0, 1.0);
  double zgyro = 0.0;
  double zacc = 0.0;
  int n = 0;
  for (const auto& r : gcs.received) {
    if (r.t_s <= 2.0)
      continue;  // past the turn-rate ramp
    if (auto imu = r.frame.as<mav::ScaledImu>()) {
      zgyro += imu->zgyro;
      zacc += imu->zacc;
      ++n;
      EXPECT_NEAR(imu->zgyro, -omega * 1000.0, 4.0 * 3.0 + 1.0);  // 4 sigma of 3 mrad/s
    }
  }
  ASSERT_GE(n, 8);
  EXPECT_NEAR(zgyro / n, -omega * 1000.0, 4.0);  // FRD: counter-clockwise is negative
  EXPECT_NEAR(zacc / n, -1000.0, 15.0);          // resting on the floor: -1 g on z-down
}

// ---- Missions ---------------------------------------------------------------------------------

mav::MissionItemInt waypoint(std::uint16_t seq, Vec2 p) {
  mav::MissionItemInt item;
  item.target_system = 1;
  item.target_component = 1;
  item.seq = seq;
  item.frame = static_cast<std::uint8_t>(mav::MavFrame::kLocalNed);
  item.command = static_cast<std::uint16_t>(mav::MavCmd::kNavWaypoint);
  item.autocontinue = 1;
  item.x = static_cast<std::int32_t>(std::lround(p.x() * 1e4));
  item.y = static_cast<std::int32_t>(std::lround(-p.y() * 1e4));  // NED east = -y
  return item;
}

// Uploads `points` (our world frame), answering every MISSION_REQUEST_INT as a GCS would;
// `reply` may alter the item. Returns the MISSION_ACK (nullopt if none within 10 s).
std::optional<mav::MissionAck> upload(Gcs& gcs, const std::vector<Vec2>& points,
                                      const std::function<void(mav::MissionItemInt&)>& reply = {}) {
  mav::MissionCount count;
  count.target_system = 1;
  count.target_component = 1;
  count.count = static_cast<std::uint16_t>(points.size());
  gcs.send(count, gcs.now());
  std::size_t seen = gcs.received.size();
  const double until = gcs.now() + 10.0;
  while (gcs.now() < until) {
    gcs.run(gcs.now() + 0.01, true, std::nullopt);
    for (; seen < gcs.received.size(); ++seen) {
      const mav::Frame frame = gcs.received[seen].frame;
      if (auto request = frame.as<mav::MissionRequestInt>()) {
        EXPECT_EQ(request->target_system, 255);
        mav::MissionItemInt item = waypoint(request->seq, points.at(request->seq));
        if (reply)
          reply(item);
        gcs.send(item, gcs.now());
      } else if (auto ack = frame.as<mav::MissionAck>()) {
        return ack;
      }
    }
  }
  return std::nullopt;
}

std::vector<std::uint16_t> reachedItems(const Gcs& gcs) {
  std::vector<std::uint16_t> out;
  for (const auto& r : gcs.all<mav::MissionItemReached>())
    out.push_back(r.seq);
  return out;
}

TEST(FirmwareMission, UploadedPathIsTravelledTurnThenStraightReportingEachWaypoint) {
  FirmwareCore core = makeCore(room(false));
  Gcs gcs(core);
  gcs.run(0.1, true, std::nullopt);
  // (0.5, 0) lies on the first leg: merged into it, reported reached with (1, 0).
  const std::vector<Vec2> path = {Vec2(0.5, 0.0), Vec2(1.0, 0.0), Vec2(1.0, 0.8), Vec2(0.2, 0.8)};
  const auto ack = upload(gcs, path);
  ASSERT_TRUE(ack);
  EXPECT_EQ(ack->type, static_cast<std::uint8_t>(mav::MavMissionResult::kAccepted));
  ASSERT_EQ(core.mission().waypoints().size(), 4u);
  EXPECT_NEAR(core.mission().waypoints()[2].y(), 0.8, 1e-4);  // NED east -> our y (left)

  gcs.command(mav::MavCmd::kMissionStart, 0.0f, gcs.now());
  const double start = gcs.now();
  while (gcs.now() < start + 60.0 && reachedItems(gcs).size() < 4)
    gcs.run(gcs.now() + 0.5, true, std::nullopt);
  gcs.run(gcs.now() + 1.0, true, std::nullopt);

  ASSERT_EQ(acksFor(gcs, mav::MavCmd::kMissionStart).size(), 1u);
  EXPECT_EQ(acksFor(gcs, mav::MavCmd::kMissionStart)[0].result, kAccepted);
  EXPECT_EQ(reachedItems(gcs), (std::vector<std::uint16_t>{0, 1, 2, 3}));
  const Pose2 end = core.simulator().odometryPose();
  EXPECT_NEAR(end.x, 0.2, 0.02);
  EXPECT_NEAR(end.y, 0.8, 0.02);
  EXPECT_NEAR(std::abs(wrapAngle(end.theta)), kPi, degToRad(5.0));  // last leg heads -x
  EXPECT_TRUE(stopped(core));
  EXPECT_EQ(behaviourStates(gcs).back(), kSucceeded);
  // The track passes through both turning points (turn on the spot, then straight).
  double near_first = 1e9;
  double near_second = 1e9;
  for (const auto& lp : gcs.all<mav::LocalPositionNed>()) {
    const Vec2 p(lp.x, -lp.y);
    near_first = std::min(near_first, (p - Vec2(1.0, 0.0)).norm());
    near_second = std::min(near_second, (p - Vec2(1.0, 0.8)).norm());
  }
  EXPECT_LT(near_first, 0.02);
  EXPECT_LT(near_second, 0.02);
  EXPECT_TRUE(gcs.saidSomething("mission complete"));
}

TEST(FirmwareMission, MissionStopsWhenGcsHeartbeatsGoMissing) {
  FirmwareCore core = makeCore(room(false));
  Gcs gcs(core);
  gcs.run(0.1, true, std::nullopt);
  ASSERT_TRUE(upload(gcs, {Vec2(2.5, 0.0)}));
  gcs.command(mav::MavCmd::kMissionStart, 0.0f, gcs.now());
  gcs.run(gcs.now() + 1.0, true, std::nullopt);
  ASSERT_FALSE(stopped(core));
  const double last_heartbeat = gcs.now();  // heartbeats every 0.5 s: the last within 0.5 s
  double stop_time = -1.0;
  while (gcs.now() < last_heartbeat + 3.0 && stop_time < 0.0) {
    gcs.run(gcs.now() + 0.01, false, std::nullopt);
    if (stopped(core))
      stop_time = gcs.now();
  }
  ASSERT_GT(stop_time, 0.0);
  EXPECT_LE(stop_time - last_heartbeat, 1.5 + 0.03);
  EXPECT_EQ(behaviourStates(gcs).back(), kAborted);
  EXPECT_TRUE(reachedItems(gcs).empty());
}

TEST(FirmwareMission, MissionStopsShortOfAWallAheadAndFails) {
  // A robot without bumpers sent through a wall 0.4 m ahead: the mission's SEGMENTS primitive
  // stops where its forward sonars see the wall inside the clearance, before touching it; the
  // mission has not reached its waypoint, so it fails. (Blocked where the sonars see nothing,
  // the executor's watchdog ends it: FirmwareMotion.WaypointsBlockedWithoutBumperContact...)
  FirmwareCore core = makeBumperlessCore(room(true));
  Gcs gcs(core);
  gcs.run(0.1, true, std::nullopt);
  ASSERT_TRUE(upload(gcs, {Vec2(1.0, 0.0)}));
  gcs.command(mav::MavCmd::kMissionStart, 0.0f, gcs.now());
  gcs.run(gcs.now() + 15.0, true, std::nullopt);
  EXPECT_EQ(behaviourStates(gcs).back(),
            static_cast<std::uint8_t>(mav::IrgsBehaviourState::kFailed));
  EXPECT_TRUE(gcs.saidSomething("mission stopped: wall ahead on leg 1 of 1"));
  EXPECT_TRUE(stopped(core));
  EXPECT_LT(core.simulator().truePose().x, 0.4);
  EXPECT_TRUE(reachedItems(gcs).empty());
}

TEST(FirmwareMission, UnsupportedItemsAreRefusedAndTheStoredMissionKept) {
  FirmwareCore core = makeCore(room(false));
  Gcs gcs(core);
  gcs.run(0.1, true, std::nullopt);
  ASSERT_TRUE(upload(gcs, {Vec2(1.0, 0.0)}));
  const auto global = upload(gcs, {Vec2(1.0, 1.0), Vec2(2.0, 1.0)}, [](mav::MissionItemInt& i) {
    i.frame = static_cast<std::uint8_t>(mav::MavFrame::kGlobalInt);
  });
  ASSERT_TRUE(global);
  EXPECT_EQ(global->type, static_cast<std::uint8_t>(mav::MavMissionResult::kUnsupportedFrame));
  const auto takeoff = upload(gcs, {Vec2(1.0, 1.0)}, [](mav::MissionItemInt& i) {
    i.command = 22;  // MAV_CMD_NAV_TAKEOFF
  });
  ASSERT_TRUE(takeoff);
  EXPECT_EQ(takeoff->type, static_cast<std::uint8_t>(mav::MavMissionResult::kUnsupported));
  ASSERT_EQ(core.mission().waypoints().size(), 1u);
  EXPECT_NEAR(core.mission().waypoints()[0].x(), 1.0, 1e-9);
  EXPECT_TRUE(gcs.saidSomething("mission item 0: frame not LOCAL_NED/FLU"));
}

TEST(FirmwareMission, SilentUploadIsReRequestedThenCancelled) {
  FirmwareCore core = makeCore(room(false));
  Gcs gcs(core);
  gcs.run(0.1, true, std::nullopt);
  mav::MissionCount count;
  count.target_system = 1;
  count.count = 3;
  gcs.send(count, gcs.now());
  gcs.run(gcs.now() + 5.0, true, std::nullopt);
  const auto requests = gcs.all<mav::MissionRequestInt>();
  EXPECT_EQ(requests.size(), 1u + MissionStore::kMaxRetries);
  for (const auto& r : requests)
    EXPECT_EQ(r.seq, 0);
  const auto acks = gcs.all<mav::MissionAck>();
  ASSERT_EQ(acks.size(), 1u);
  EXPECT_EQ(acks[0].type, static_cast<std::uint8_t>(mav::MavMissionResult::kOperationCancelled));
  EXPECT_FALSE(core.mission().uploading());
  EXPECT_TRUE(gcs.saidSomething("timed out"));
}

TEST(FirmwareMission, DownloadReturnsTheUploadedWaypoints) {
  FirmwareCore core = makeCore(room(false));
  Gcs gcs(core);
  gcs.run(0.1, true, std::nullopt);
  ASSERT_TRUE(upload(gcs, {Vec2(1.0, -0.5), Vec2(1.5, 0.25)}));
  mav::MissionRequestList list;
  list.target_system = 1;
  gcs.send(list, gcs.now());
  mav::MissionRequestInt request;
  request.target_system = 1;
  request.seq = 1;
  gcs.send(request, gcs.now());
  request.seq = 7;  // beyond the mission
  gcs.send(request, gcs.now());
  gcs.run(gcs.now() + 0.1, true, std::nullopt);
  ASSERT_EQ(gcs.all<mav::MissionCount>().size(), 1u);
  EXPECT_EQ(gcs.all<mav::MissionCount>()[0].count, 2);
  const auto items = gcs.all<mav::MissionItemInt>();
  ASSERT_EQ(items.size(), 1u);
  EXPECT_EQ(items[0].seq, 1);
  EXPECT_EQ(items[0].x, 15000);
  EXPECT_EQ(items[0].y, -2500);  // our y left 0.25 m = NED east -0.25 m
  EXPECT_EQ(gcs.all<mav::MissionAck>().back().type,
            static_cast<std::uint8_t>(mav::MavMissionResult::kInvalidSequence));
}

TEST(FirmwareMission, StartWithoutAMissionIsDenied) {
  FirmwareCore core = makeCore(room(false));
  Gcs gcs(core);
  gcs.run(0.1, true, std::nullopt);
  gcs.command(mav::MavCmd::kMissionStart, 0.0f, gcs.now());
  gcs.run(0.2, true, std::nullopt);
  ASSERT_EQ(acksFor(gcs, mav::MavCmd::kMissionStart).size(), 1u);
  EXPECT_EQ(acksFor(gcs, mav::MavCmd::kMissionStart)[0].result, kDenied);
}

TEST(FirmwareMission, LegsMergeCollinearWaypointsAndTagTheLastItemReached) {
  const auto legs = missionLegs(Pose2{0.0, 0.0, 0.0},
                                {Vec2(0.5, 0.0), Vec2(1.0, 0.0), Vec2(1.0, 1.0), Vec2(1.0, 1.0)});
  ASSERT_EQ(legs.size(), 2u);
  EXPECT_EQ(legs[0].last_item, 1);
  EXPECT_NEAR(legs[0].segment.distance_m, 1.0, 1e-12);
  EXPECT_NEAR(legs[0].segment.turn_rad, 0.0, 1e-12);
  EXPECT_EQ(legs[1].last_item, 3);  // the repeated last point is reached with it
  EXPECT_NEAR(legs[1].segment.turn_rad, kPi / 2.0, 1e-12);
  EXPECT_TRUE(missionLegs(Pose2{1.0, 1.0, 0.0}, {Vec2(1.0, 1.0)}).empty());
}

// ---- FOLLOW_WALL -------------------------------------------------------------------------------

mav::CommandLong followWall(float distance, mav::IrgsWallSide side, float speed, float travel) {
  mav::CommandLong c;
  c.target_system = 1;
  c.command = static_cast<std::uint16_t>(mav::MavCmd::kIrgsFollowWall);
  c.param1 = distance;
  c.param2 = static_cast<float>(side);
  c.param3 = speed;
  c.param4 = travel;
  return c;
}

TEST(FirmwareWallFollow, FollowsTheWallOnTheRightAtTheSetDistance) {
  // The room's south wall (y = -3) 0.3 m to the right of the start, heading +x.
  FirmwareCore core = makeCore(room(false, Pose2{-2.0, -2.7, 0.0}));
  Gcs gcs(core);
  gcs.run(0.1, true, std::nullopt);
  gcs.send(followWall(0.3f, mav::IrgsWallSide::kRight, 0.15f, 0.0f), gcs.now());
  double worst = 0.0;
  while (gcs.now() < 10.0) {
    gcs.run(gcs.now() + 0.1, true, std::nullopt);
    if (gcs.now() > 2.0)
      worst = std::max(worst, std::abs(core.simulator().truePose().y + 3.0 - 0.3));
  }
  const auto acks = acksFor(gcs, mav::MavCmd::kIrgsFollowWall);
  ASSERT_EQ(acks.size(), 1u);
  EXPECT_EQ(acks[0].result, kAccepted);
  EXPECT_GT(core.simulator().truePose().x, -2.0 + 0.8);  // made way along the wall
  EXPECT_LT(worst, 0.08);
  EXPECT_EQ(behaviourStates(gcs).back(), kRunning);
  EXPECT_GT(gcs.all<mav::IrgsBehaviourStatus>().back().progress, 0.8f);

  gcs.command(mav::MavCmd::kIrgsStop, 0.0f, gcs.now());
  gcs.run(gcs.now() + 1.5, true, std::nullopt);
  EXPECT_TRUE(stopped(core));
  EXPECT_EQ(behaviourStates(gcs).back(), kAborted);
}

TEST(FirmwareWallFollow, TravelLimitEndsTheBehaviourSuccessfully) {
  FirmwareCore core = makeCore(room(false, Pose2{-2.0, -2.7, 0.0}));
  Gcs gcs(core);
  gcs.run(0.1, true, std::nullopt);
  gcs.send(followWall(0.3f, mav::IrgsWallSide::kRight, 0.2f, 0.5f), gcs.now());
  gcs.run(8.0, true, std::nullopt);
  EXPECT_EQ(behaviourStates(gcs).back(), kSucceeded);
  EXPECT_NEAR(core.simulator().odometryPose().x, -2.0 + 0.5, 0.08);
  EXPECT_TRUE(stopped(core));
}

TEST(FirmwareWallFollow, StopsWhenGcsHeartbeatsGoMissing) {
  FirmwareCore core = makeCore(room(false, Pose2{-2.0, -2.7, 0.0}));
  Gcs gcs(core);
  gcs.run(0.1, true, std::nullopt);  // the only heartbeat: 0.01 s
  gcs.send(followWall(0.3f, mav::IrgsWallSide::kRight, 0.2f, 0.0f), gcs.now());
  double stop_time = -1.0;
  while (gcs.now() < 3.0) {
    gcs.run(gcs.now() + 0.01, false, std::nullopt);
    if (gcs.now() > 0.5 && stopped(core) && stop_time < 0.0)
      stop_time = gcs.now();
  }
  ASSERT_GT(stop_time, 0.0);
  EXPECT_LE(stop_time, 0.01 + 1.5 + 0.03);
  EXPECT_EQ(behaviourStates(gcs).back(), kAborted);
}

TEST(FirmwareWallFollow, InvalidArgumentsAreDenied) {
  FirmwareCore core = makeCore(room(false));
  Gcs gcs(core);
  gcs.run(0.1, true, std::nullopt);
  gcs.send(followWall(0.0f, mav::IrgsWallSide::kRight, 0.2f, 0.0f), gcs.now());
  auto bad_side = followWall(0.3f, mav::IrgsWallSide::kRight, 0.2f, 0.0f);
  bad_side.param2 = 7.0f;
  gcs.send(bad_side, gcs.now());
  gcs.send(
      followWall(std::numeric_limits<float>::quiet_NaN(), mav::IrgsWallSide::kLeft, 0.2f, 0.0f),
      gcs.now());
  gcs.run(0.3, true, std::nullopt);
  const auto acks = acksFor(gcs, mav::MavCmd::kIrgsFollowWall);
  ASSERT_EQ(acks.size(), 3u);
  for (const auto& a : acks)
    EXPECT_EQ(a.result, kDenied);
  EXPECT_TRUE(stopped(core));
}

}  // namespace
}  // namespace irgs::app

namespace irgs::app {
namespace {

// docs/protocol.md section 11: the default streams (with SYS_STATUS and SCALED_IMU) fit a
// 115200 baud UART with headroom for commands and STATUSTEXT.
TEST(FirmwareStreams, DefaultStreamsFitA115200BaudUart) {
  FirmwareCore core = makeCore(room(true));
  Gcs gcs(core);
  gcs.run(3.0, true, std::make_pair<std::int16_t, std::int16_t>(0, 300));
  std::size_t bytes = 0;
  for (const auto& r : gcs.received)
    if (r.t_s > 1.0)
      bytes += 12u + r.frame.payload_length;  // v2 header + checksum, unsigned
  const double per_second = static_cast<double>(bytes) / 2.0;
  RecordProperty("bytes_per_second", static_cast<int>(per_second));
  EXPECT_LT(per_second, 11520.0 * 0.95) << per_second << " B/s";
  std::printf("default streams: %.0f B/s = %.1f %% of 115200 baud\n", per_second,
              100.0 * per_second / 11520.0);
}

// The floor-sensor robot (no sonars) and the three-caster robot (three sonars at 25 Hz, no
// IRGS_ENCODER_TICKS) with their extra streams at the default rates stay inside the same 95 %
// of a 115200 baud UART.
TEST(FirmwareStreams, MouseAndCasterRobotStreamsFitA115200BaudUart) {
  for (const char* name : {"mouse_type20_004.json", "caster3_000.json"}) {
    SCOPED_TRACE(name);
    const RobotProfileResult robot =
        loadRobotProfileFile(std::string(IRGS_SOURCE_DIR) + "/resources/robots/" + name);
    ASSERT_TRUE(robot.profile.has_value());
    SimConfig sim;
    sim.seed = 7;
    FirmwareCore core(Simulator(room(true), *robot.profile, typicalSimConfig(sim)), {});
    Gcs gcs(core);
    gcs.run(3.0, true, std::make_pair<std::int16_t, std::int16_t>(0, 300));
    std::size_t bytes = 0;
    std::size_t mouse = 0, casters = 0, ticks = 0;
    for (const auto& r : gcs.received) {
      if (r.t_s <= 1.0)
        continue;
      bytes += 12u + r.frame.payload_length;
      mouse += r.frame.message_id == mav::IrgsMouseCounts::kId ? 1u : 0u;
      casters += r.frame.message_id == mav::IrgsCasterEncoders::kId ? 1u : 0u;
      ticks += r.frame.message_id == mav::IrgsEncoderTicks::kId ? 1u : 0u;
    }
    const bool caster_robot = robot.profile->drive.type == DriveType::kThreeCaster;
    EXPECT_NEAR(static_cast<double>(caster_robot ? casters : mouse), 40.0, 1.0);  // 20 Hz
    EXPECT_EQ(caster_robot ? mouse : casters, 0u);
    EXPECT_EQ(ticks == 0u, caster_robot);
    const double per_second = static_cast<double>(bytes) / 2.0;
    EXPECT_LT(per_second, 11520.0 * 0.95) << per_second << " B/s";
    std::printf("%s streams: %.0f B/s = %.1f %% of 115200 baud\n", name, per_second,
                100.0 * per_second / 11520.0);
  }
}

}  // namespace
}  // namespace irgs::app
