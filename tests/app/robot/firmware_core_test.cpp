// FirmwareCore over the wire: a fake ground station encodes MAVLink frames with its own
// FrameEncoder and decodes what the firmware sends, driven by a fake clock (no sleeps).

#include "app/robot/firmware_core.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "comms/mavlink/messages.hpp"
#include "tests/app/robot/firmware_test_support.hpp"

namespace irgs::app {
namespace {

namespace mav = comms::mavlink;
using namespace firmware_test;  // NOLINT: the test support vocabulary

TEST(FirmwareCore, ManualControlForwardDrivesForwardAndOdometryShowsIt) {
  FirmwareCore core = makeCore(room(false));
  Gcs gcs(core);
  gcs.run(1.5, true, std::make_pair<std::int16_t, std::int16_t>(1000, 0));
  const Pose2 pose = core.simulator().truePose();
  EXPECT_GT(pose.x, 0.25);  // 0.3 m/s after a 0.6 s ramp
  EXPECT_NEAR(pose.y, 0.0, 1e-6);
  const auto odometry = gcs.all<mav::Odometry>();
  ASSERT_FALSE(odometry.empty());
  EXPECT_GT(odometry.back().x, 0.25f);
  EXPECT_NEAR(odometry.back().vx, 0.3f, 1e-3f);
  EXPECT_EQ(odometry.back().frame_id, static_cast<std::uint8_t>(mav::MavFrame::kLocalNed));
  EXPECT_EQ(odometry.back().child_frame_id, static_cast<std::uint8_t>(mav::MavFrame::kBodyFrd));
  const auto local = gcs.all<mav::LocalPositionNed>();
  ASSERT_FALSE(local.empty());
  EXPECT_FLOAT_EQ(local.back().x, odometry.back().x);
  EXPECT_GT(local.back().vx, 0.29f);
}

TEST(FirmwareCore, PositiveManualControlYawTurnsClockwise) {
  FirmwareCore core = makeCore(room(false));
  Gcs gcs(core);
  gcs.run(1.0, true, std::make_pair<std::int16_t, std::int16_t>(0, 500));
  EXPECT_LT(core.simulator().truePose().theta, -0.2);  // clockwise = negative CCW heading
  const auto odometry = gcs.all<mav::Odometry>();
  ASSERT_FALSE(odometry.empty());
  EXPECT_GT(odometry.back().yawspeed, 0.5f);  // FRD yaw rate: clockwise positive
  EXPECT_GT(odometry.back().q[3], 0.0f);      // yaw_frd = -theta > 0
}

TEST(FirmwareCore, OdometryConvertsFluPoseToFrd) {
  FirmwareCore core = makeCore(room(false, Pose2{1.0, 2.0, 0.5}));
  Gcs gcs(core);
  gcs.run(0.1, true, std::nullopt);
  const auto odometry = gcs.all<mav::Odometry>();
  ASSERT_FALSE(odometry.empty());
  const auto& o = odometry.back();
  EXPECT_NEAR(o.x, 1.0f, 1e-5f);
  EXPECT_NEAR(o.y, -2.0f, 1e-5f);
  EXPECT_NEAR(2.0 * std::atan2(o.q[3], o.q[0]), -0.5, 1e-5);
  EXPECT_TRUE(std::isnan(o.pose_covariance[0]));
  const auto local = gcs.all<mav::LocalPositionNed>();
  ASSERT_FALSE(local.empty());
  EXPECT_NEAR(local.back().y, -2.0f, 1e-5f);
  const auto attitude = gcs.all<mav::Attitude>();
  ASSERT_FALSE(attitude.empty());
  EXPECT_NEAR(attitude.back().yaw, -0.5f, 1e-5f);
}

TEST(FirmwareCore, TeleopExpiresAndTheRobotStopsWithinHalfASecond) {
  FirmwareCore core = makeCore(room(false));
  Gcs gcs(core);
  gcs.run(1.0, true, std::make_pair<std::int16_t, std::int16_t>(1000, 0));
  ASSERT_FALSE(stopped(core));
  const double last_command = 0.91;  // MANUAL_CONTROL went out at 0.01, 0.11, ..., 0.91
  double stop_time = -1.0;
  while (gcs.now() < 3.0) {
    gcs.run(gcs.now() + 0.01, true, std::nullopt);
    if (stopped(core) && stop_time < 0.0)
      stop_time = gcs.now();
  }
  ASSERT_GT(stop_time, 0.0);
  EXPECT_LE(stop_time - last_command, 0.5);
  EXPECT_GE(stop_time - last_command, core.config().teleop_timeout_s - 0.02);
  EXPECT_TRUE(gcs.saidSomething("teleop timeout"));
  EXPECT_TRUE(core.safety().gcs_alive);
}

TEST(FirmwareCore, MissingGcsHeartbeatsStopMotionAfterTheTimeout) {
  FirmwareConfig config;
  config.teleop_timeout_s = 10.0;  // isolate the heartbeat rule
  FirmwareCore core = makeCore(room(false), config);
  Gcs gcs(core);
  // The only heartbeat goes out at 0.01 s (the next would be due at 0.51 s).
  gcs.run(0.3, true, std::make_pair<std::int16_t, std::int16_t>(300, 0));
  ASSERT_FALSE(stopped(core));
  double stop_time = -1.0;
  while (gcs.now() < 3.0) {
    gcs.run(gcs.now() + 0.01, false, std::make_pair<std::int16_t, std::int16_t>(300, 0));
    if (stopped(core) && stop_time < 0.0)
      stop_time = gcs.now();
  }
  ASSERT_GT(stop_time, 0.0);
  EXPECT_LE(stop_time, 0.01 + config.gcs_timeout_s + 0.03);
  EXPECT_GE(stop_time, 0.01 + config.gcs_timeout_s - 0.02);
  EXPECT_TRUE(gcs.saidSomething("heartbeat lost"));
  EXPECT_FALSE(core.safety().gcs_alive);
  EXPECT_TRUE(stopped(core));  // MANUAL_CONTROL kept arriving and was refused
}

TEST(FirmwareCore, ManualControlWithoutAnyGcsHeartbeatIsRefused) {
  FirmwareCore core = makeCore(room(false));
  Gcs gcs(core);
  gcs.run(1.0, false, std::make_pair<std::int16_t, std::int16_t>(1000, 0));
  EXPECT_NEAR(core.simulator().truePose().x, 0.0, 1e-9);
  EXPECT_TRUE(gcs.saidSomething("no GCS heartbeat"));
}

TEST(FirmwareCore, OwnHeartbeatsEchoedBackDoNotCountAsAGroundStation) {
  FirmwareCore core = makeCore(room(false));
  mav::FrameEncoder echo(1, 1);  // our own system id, as a pty in echo mode would return it
  mav::Heartbeat hb;
  core.receiveBytes(echo.encode(hb).view(), 0.0);
  core.advance(0.05);
  EXPECT_FALSE(core.safety().gcs_alive);
}

TEST(FirmwareCore, EmergencyStopLatchesUntilReleased) {
  FirmwareCore core = makeCore(room(false));
  Gcs gcs(core);
  gcs.run(1.0, true, std::make_pair<std::int16_t, std::int16_t>(1000, 0));
  ASSERT_FALSE(stopped(core));
  gcs.command(mav::MavCmd::kIrgsEmergencyStop, 1.0f, gcs.now());
  gcs.run(gcs.now() + 0.02, true, std::make_pair<std::int16_t, std::int16_t>(1000, 0));
  EXPECT_TRUE(stopped(core));  // braked at once, not ramped down
  const double x_at_stop = core.simulator().truePose().x;
  gcs.run(gcs.now() + 2.5, true, std::make_pair<std::int16_t, std::int16_t>(1000, 0));
  EXPECT_NEAR(core.simulator().truePose().x, x_at_stop, 1e-9);
  EXPECT_TRUE(core.safety().estop_latched);
  const auto acks = gcs.all<mav::CommandAck>();
  ASSERT_EQ(acks.size(), 1u);
  EXPECT_EQ(acks[0].result, static_cast<std::uint8_t>(mav::MavResult::kAccepted));
  EXPECT_EQ(gcs.all<mav::Heartbeat>().back().system_status,
            static_cast<std::uint8_t>(mav::MavState::kEmergency));
  EXPECT_TRUE(gcs.saidSomething("EMERGENCY STOP"));

  gcs.command(mav::MavCmd::kIrgsEmergencyStop, 0.0f, gcs.now());
  gcs.run(gcs.now() + 1.0, true, std::make_pair<std::int16_t, std::int16_t>(1000, 0));
  EXPECT_GT(core.simulator().truePose().x, x_at_stop + 0.05);
  EXPECT_FALSE(core.safety().estop_latched);
}

TEST(FirmwareCore, BumperContactStopsAndRefusesForwardButAllowsReversing) {
  FirmwareCore core = makeCore(room(true));
  Gcs gcs(core);
  gcs.run(3.0, true, std::make_pair<std::int16_t, std::int16_t>(1000, 0));
  EXPECT_NE(core.safety().bumpers, 0u);
  EXPECT_TRUE(core.safety().forward_blocked);
  EXPECT_TRUE(stopped(core));
  EXPECT_TRUE(gcs.saidSomething("bumper"));
  const double x_contact = core.simulator().truePose().x;
  EXPECT_GT(x_contact, 0.2);
  bool contact_reported = false;
  for (const auto& c : gcs.all<mav::IrgsContact>())
    contact_reported = contact_reported || c.bumpers != 0;
  EXPECT_TRUE(contact_reported);

  gcs.run(gcs.now() + 1.0, true, std::make_pair<std::int16_t, std::int16_t>(-1000, 0));
  EXPECT_LT(core.simulator().truePose().x, x_contact - 0.05);
  EXPECT_EQ(core.safety().bumpers, 0u);
}

TEST(FirmwareCore, StreamsTelemetryAtTheConfiguredRates) {
  FirmwareCore core = makeCore(room(false));
  Gcs gcs(core);
  gcs.run(3.0, true, std::nullopt);
  const double span = 2.0;  // count over (1, 3] to skip the start
  const auto hb = gcs.all<mav::Heartbeat>(1.0);
  EXPECT_NEAR(static_cast<double>(hb.size()), span, 1.0);
  EXPECT_EQ(hb.back().type, static_cast<std::uint8_t>(mav::MavType::kGroundRover));
  EXPECT_NEAR(static_cast<double>(gcs.all<mav::Odometry>(1.0).size()), 20.0 * span, 1.0);
  EXPECT_NEAR(static_cast<double>(gcs.all<mav::IrgsEncoderTicks>(1.0).size()), 20.0 * span, 1.0);
  EXPECT_NEAR(static_cast<double>(gcs.all<mav::LocalPositionNed>(1.0).size()), 20.0 * span, 1.0);
  EXPECT_TRUE(gcs.all<mav::IrgsSonarScan>().empty());  // off by default at 115200
  EXPECT_NEAR(static_cast<double>(gcs.all<mav::IrgsContact>(1.0).size()), 10.0 * span, 1.0);
  // Eight sonars at 10 Hz each: every reading goes out once as DISTANCE_SENSOR.
  const auto ds = gcs.all<mav::DistanceSensor>(1.0);
  EXPECT_NEAR(static_cast<double>(ds.size()), 8 * 10.0 * span, 8.0);
  std::vector<int> per_sensor(8, 0);
  for (const auto& d : ds) {
    ASSERT_LT(d.id, 8);
    ++per_sensor[d.id];
    EXPECT_EQ(d.type, static_cast<std::uint8_t>(mav::MavDistanceSensor::kUltrasound));
    EXPECT_EQ(d.min_distance, 5);
    EXPECT_EQ(d.max_distance, 400);
    EXPECT_LE(d.current_distance, 401);
    const auto want = d.id == 1 || d.id == 5   ? mav::MavSensorOrientation::kYaw270  // left
                      : d.id == 3 || d.id == 7 ? mav::MavSensorOrientation::kYaw90   // right
                                               : mav::MavSensorOrientation::kNone;
    EXPECT_EQ(d.orientation, static_cast<std::uint8_t>(want)) << "sonar " << int(d.id);
  }
  for (int n : per_sensor)
    EXPECT_NEAR(n, 20, 1);
}

TEST(FirmwareCore, SlowLinkProfileSendsOnlyTheCompactStreamsWithinA9600BaudBudget) {
  FirmwareCore core = makeCore(room(true), slowLinkFirmwareConfig());
  Gcs gcs(core);
  gcs.run(3.0, true, std::nullopt);
  EXPECT_TRUE(gcs.all<mav::Odometry>().empty());
  EXPECT_TRUE(gcs.all<mav::LocalPositionNed>().empty());
  EXPECT_TRUE(gcs.all<mav::DistanceSensor>().empty());
  EXPECT_NEAR(static_cast<double>(gcs.all<mav::IrgsPose2d>(1.0).size()), 20.0, 1.0);
  const auto scans = gcs.all<mav::IrgsSonarScan>(1.0);
  EXPECT_NEAR(static_cast<double>(scans.size()), 10.0, 1.0);
  ASSERT_FALSE(scans.empty());
  EXPECT_EQ(scans.back().count, 8);
  EXPECT_NEAR(scans.back().range[0], 300, 20);  // wall 0.30 m ahead of sonar 0, in mm
  EXPECT_EQ(scans.back().fired, 0xFF);          // every 10 Hz sonar fired within 0.2 s
  std::size_t bytes = 0;
  for (const auto& r : gcs.received)
    if (r.t_s > 1.0)
      bytes += 12u + r.frame.payload_length;
  EXPECT_LT(static_cast<double>(bytes) / 2.0, 960.0 * 0.8);
}

TEST(FirmwareCore, SonarRangeMatchesTheWallAhead) {
  FirmwareCore core = makeCore(room(true));
  Gcs gcs(core);
  gcs.run(0.5, true, std::nullopt);
  // Sonar 0 sits at x 0.10 facing forward; the wall is at x 0.40: 30 cm.
  bool seen = false;
  for (const auto& d : gcs.all<mav::DistanceSensor>())
    if (d.id == 0) {
      EXPECT_NEAR(d.current_distance, 30, 2);
      seen = true;
    }
  EXPECT_TRUE(seen);
}

TEST(FirmwareCore, StopCommandIsAcknowledgedAndUnknownCommandsAreUnsupported) {
  FirmwareCore core = makeCore(room(false));
  Gcs gcs(core);
  gcs.run(0.5, true, std::make_pair<std::int16_t, std::int16_t>(1000, 0));
  gcs.command(mav::MavCmd::kIrgsStop, 0.0f, gcs.now());
  gcs.command(mav::MavCmd::kDoSetMode, 1.0f, gcs.now());
  gcs.run(gcs.now() + 1.0, true, std::nullopt);
  const auto acks = gcs.all<mav::CommandAck>();
  ASSERT_EQ(acks.size(), 2u);
  EXPECT_EQ(acks[0].command, static_cast<std::uint16_t>(mav::MavCmd::kIrgsStop));
  EXPECT_EQ(acks[0].result, static_cast<std::uint8_t>(mav::MavResult::kAccepted));
  EXPECT_EQ(acks[1].result, static_cast<std::uint8_t>(mav::MavResult::kUnsupported));
  EXPECT_TRUE(stopped(core));
}

TEST(FirmwareCore, MoveDistanceDrivesTheDistanceOnOdometryAndSucceeds) {
  FirmwareCore core = makeCore(room(false));
  Gcs gcs(core);
  gcs.run(0.1, true, std::nullopt);
  mav::CommandLong move;
  move.target_system = 1;
  move.command = static_cast<std::uint16_t>(mav::MavCmd::kIrgsMoveDistance);
  move.param1 = 0.5f;
  move.param2 = 0.2f;
  gcs.send(move, gcs.now());
  gcs.run(5.0, true, std::nullopt);
  EXPECT_NEAR(core.simulator().odometryPose().x, 0.5, 0.01);
  EXPECT_TRUE(stopped(core));
  ASSERT_EQ(gcs.all<mav::CommandAck>().size(), 1u);
  EXPECT_EQ(gcs.all<mav::CommandAck>()[0].result,
            static_cast<std::uint8_t>(mav::MavResult::kAccepted));
  const auto states = behaviourStates(gcs);
  ASSERT_GE(states.size(), 2u);
  EXPECT_EQ(states.front(), kRunning);
  EXPECT_EQ(states.back(), kSucceeded);
  EXPECT_NEAR(gcs.all<mav::IrgsBehaviourStatus>().back().progress, 0.5f, 0.01f);
}

TEST(FirmwareCore, TurnAngleTurnsCounterClockwiseByTheAngle) {
  FirmwareCore core = makeCore(room(false));
  Gcs gcs(core);
  gcs.run(0.1, true, std::nullopt);
  gcs.command(mav::MavCmd::kIrgsTurnAngle, static_cast<float>(kPi / 2.0), gcs.now());
  gcs.run(5.0, true, std::nullopt);
  EXPECT_NEAR(core.simulator().odometryPose().theta, kPi / 2.0, degToRad(1.0));
  EXPECT_EQ(behaviourStates(gcs).back(), kSucceeded);
}

TEST(FirmwareCore, BehaviourStopsWhenGcsHeartbeatsGoMissing) {
  FirmwareCore core = makeCore(room(false));
  Gcs gcs(core);
  gcs.run(0.1, true, std::nullopt);  // the only heartbeat: 0.01 s
  gcs.command(mav::MavCmd::kIrgsMoveDistance, 2.5f, gcs.now());
  double stop_time = -1.0;
  while (gcs.now() < 3.0) {
    gcs.run(gcs.now() + 0.01, false, std::nullopt);
    if (gcs.now() > 0.5 && stopped(core) && stop_time < 0.0)
      stop_time = gcs.now();
  }
  ASSERT_GT(stop_time, 0.0);
  EXPECT_LE(stop_time, 0.01 + 1.5 + 0.03);
  EXPECT_EQ(behaviourStates(gcs).back(), kAborted);
  EXPECT_LT(core.simulator().odometryPose().x, 1.0);
}

TEST(FirmwareCore, BehavioursAreDeniedWhileEstopped) {
  FirmwareCore core = makeCore(room(false));
  Gcs gcs(core);
  gcs.run(0.1, true, std::nullopt);
  gcs.command(mav::MavCmd::kIrgsEmergencyStop, 1.0f, gcs.now());
  gcs.command(mav::MavCmd::kIrgsMoveDistance, 1.0f, gcs.now());
  gcs.run(1.0, true, std::nullopt);
  const auto acks = gcs.all<mav::CommandAck>();
  ASSERT_EQ(acks.size(), 2u);
  EXPECT_EQ(acks[1].result, static_cast<std::uint8_t>(mav::MavResult::kDenied));
  EXPECT_NEAR(core.simulator().truePose().x, 0.0, 1e-9);
}

TEST(FirmwareCore, RejectsNonPositiveTimeouts) {
  FirmwareConfig config;
  config.gcs_timeout_s = 0.0;
  EXPECT_THROW(makeCore(room(false), config), std::invalid_argument);
}

}  // namespace
}  // namespace irgs::app
