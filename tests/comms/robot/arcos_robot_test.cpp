// ArcosRobot against the virtual Pioneer (ArcosFirmware) served on a real pty pair: handshake and
// identity, telemetry conversion, driving, the robot's watchdog when PULSEs stop, link loss and
// reconnection. Plus the pure pieces: velocity arguments, SIP conversion, profile parameters.

#include <gtest/gtest.h>

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <functional>
#include <string>
#include <thread>

#include "comms/arcos/arcos_sip.hpp"
#include "comms/robot/arcos_params.hpp"
#include "comms/robot/arcos_robot.hpp"
#include "comms/robot/arcos_telemetry.hpp"
#include "comms/transport/io_thread.hpp"
#include "core/robot/robot_profile_file.hpp"
#include "core/sim/sim_presets.hpp"
#include "tests/comms/robot/arcos_pty_server.hpp"

namespace irgs::comms {
namespace {

using Clock = std::chrono::steady_clock;
using testing::ArcosPtyServer;

RobotProfile pioneer(const std::string& model) {
  auto loaded = loadRobotProfileFile(std::string(IRGS_SOURCE_DIR) + "/resources/robots/pioneer_" +
                                     model + ".json");
  if (!loaded.profile)
    throw std::runtime_error("cannot load pioneer_" + model);
  return *loaded.profile;
}

WorldMap room() {
  WorldMap map;
  Wall box;
  box.id = "box";
  box.points = {Vec2(-3, -3), Vec2(6, -3), Vec2(6, 3), Vec2(-3, 3)};
  box.closed = true;
  map.walls.push_back(box);
  return map;
}

// The virtual Pioneer in strict mode: what a real robot would drop, it drops (and counts).
std::unique_ptr<app::ArcosFirmware> firmware(app::ArcosFirmwareConfig config = {}) {
  config.strict = true;
  return std::make_unique<app::ArcosFirmware>(
      Simulator(room(), pioneer("p3dx"), idealSimConfig(SimConfig{})), config);
}

LinkUrl urlOf(const std::string& text) {
  auto parsed = parseLinkUrl(text);
  if (!parsed.url)
    throw std::runtime_error(parsed.error);
  return *parsed.url;
}

// Polls `done` every 10 ms, draining the robot's samples into `samples`, until it holds or
// `timeout_s` passes (a deadline, not a sleep the result depends on).
bool waitFor(ArcosRobot& robot, std::vector<TelemetrySample>& samples,
             const std::function<bool()>& done, double timeout_s) {
  const auto t0 = Clock::now();
  while (std::chrono::duration<double>(Clock::now() - t0).count() < timeout_s) {
    for (auto& s : robot.update(0.0))
      samples.push_back(std::move(s));
    if (done())
      return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return false;
}

TEST(ArcosRobotPure, VelocityArgumentsAreMillimetresAndDegreesClampedToTheLimits) {
  MotionLimits limits;
  limits.max_speed_mps = 1.2;
  limits.max_turn_rate_radps = degToRad(300.0);
  auto a = arcosVelocityArguments({0.2504, degToRad(-30.4)}, limits);
  EXPECT_EQ(a.vel_mmps, 250);
  EXPECT_EQ(a.rvel_degps, -30);
  a = arcosVelocityArguments({-5.0, 100.0}, limits);
  EXPECT_EQ(a.vel_mmps, -1200);
  EXPECT_EQ(a.rvel_degps, 300);
  EXPECT_THROW(arcosVelocityArguments({std::nan(""), 0.0}, limits), std::invalid_argument);
}

TEST(ArcosRobotPure, PioneerProfilesCarryTheirConversionFactors) {
  const ArcosParamsResult dx = arcosParamsFromProfile(pioneer("p3dx"));
  EXPECT_TRUE(dx.found);
  EXPECT_TRUE(dx.warnings.empty());
  EXPECT_EQ(dx.params.subclass, "p3dx-sh");
  EXPECT_DOUBLE_EQ(dx.params.diff_conv, 0.0056);
  EXPECT_EQ(dx.params.vel2_divisor, 20);
  EXPECT_EQ(arcosParamsFromProfile(pioneer("p3at")).params.diff_conv, 0.0034);
  EXPECT_EQ(arcosParamsFromProfile(pioneer("amigo")).params.subclass, "amigo-sh");
  EXPECT_EQ(pioneer("amigo").sonars.size(), 8u);
  EXPECT_EQ(pioneer("peoplebot").sonars.size(), 32u);
  // ARIA p3dx-sh.p "SonarUnit 1 114 119 50".
  const SonarSpec& s1 = pioneer("p3dx").sonars[1];
  EXPECT_DOUBLE_EQ(s1.mount.x, 0.114);
  EXPECT_DOUBLE_EQ(s1.mount.y, 0.119);
  EXPECT_NEAR(s1.mount.theta, degToRad(50.0), 1e-12);

  RobotProfile bad = pioneer("p3dx");
  bad.extra["arcos"]["dist_conv_factor"] = -1;
  bad.extra["arcos"]["vel2_divisor"] = 2.5;
  const ArcosParamsResult r = arcosParamsFromProfile(bad);
  EXPECT_EQ(r.warnings.size(), 2u);
  EXPECT_EQ(r.params.dist_conv_mm, 1.0);
  EXPECT_EQ(r.params.vel2_divisor, 20);
}

TEST(ArcosRobotPure, SipsBecomeSamplesInSiUnits) {
  RobotProfile profile = pioneer("p3dx");
  ArcosTelemetryConverter converter(profile, arcosParamsFromProfile(profile).params);
  arcos::StandardSip sip;
  sip.x_raw = 32000;  // -768 mm as a signed 15-bit start
  sip.y_raw = 250;
  sip.theta_raw = 1024;  // 90 deg
  sip.left_velocity = 100;
  sip.right_velocity = 300;
  sip.sonars = {{3, 1500}, {7, 5000}, {40, 100}};
  TelemetrySample s = converter.convert(sip, 1.0);
  EXPECT_NEAR(s.odometry_pose.x, -0.768, 1e-9);
  EXPECT_NEAR(s.odometry_pose.y, 0.25, 1e-9);
  EXPECT_NEAR(s.odometry_pose.theta, 1024 * 0.001534, 1e-12);
  EXPECT_NEAR(s.measured_velocity.linear_mps, 0.2, 1e-12);
  EXPECT_NEAR(s.measured_velocity.angular_radps, 100 * 0.0056, 1e-12);  // (R - L)/2 * Diff
  ASSERT_EQ(s.sonar.size(), 2u);
  EXPECT_EQ(s.sonar[0].sensor, 3);
  EXPECT_TRUE(s.sonar[0].echo);
  EXPECT_DOUBLE_EQ(s.sonar[0].range_m, 1.5);
  EXPECT_FALSE(s.sonar[1].echo);  // at the 5 m max range
  EXPECT_EQ(converter.skippedSonars(), 1u);
  // Forward across the wrap: 32000 -> 200 is +968 units.
  sip.x_raw = 200;
  sip.rotational_velocity = 155;  // 15.5 deg/s preferred over the wheel difference
  s = converter.convert(sip, 1.1);
  EXPECT_NEAR(s.odometry_pose.x, 0.2, 1e-9);
  EXPECT_NEAR(s.measured_velocity.angular_radps, degToRad(15.5), 1e-12);
}

TEST(ArcosRobotPure, AnAnchorPutsTheFirstSipAtTheStartPoseAndAReconnectionContinues) {
  RobotProfile profile = pioneer("p3dx");
  ArcosTelemetryConverter converter(profile, arcosParamsFromProfile(profile).params);
  const Pose2 start{3.0, 1.6, kPi / 2.0};
  converter.setAnchor(start);
  arcos::StandardSip sip;  // ARCOS after OPEN: (0, 0, 0)
  TelemetrySample s = converter.convert(sip, 0.0);
  EXPECT_NEAR(s.odometry_pose.x, 3.0, 1e-9);
  EXPECT_NEAR(s.odometry_pose.y, 1.6, 1e-9);
  EXPECT_NEAR(s.odometry_pose.theta, kPi / 2.0, 1e-9);
  sip.x_raw = 1000;  // 1 m forward in ARCOS's frame = +y in the map (the robot faces +y)
  s = converter.convert(sip, 0.1);
  EXPECT_NEAR(s.odometry_pose.x, 3.0, 1e-9);
  EXPECT_NEAR(s.odometry_pose.y, 2.6, 1e-9);
  // The link drops; the robot counts from zero again after the new OPEN: no jump.
  converter.reset();
  sip.x_raw = 0;
  s = converter.convert(sip, 5.0);
  EXPECT_NEAR(s.odometry_pose.x, 3.0, 1e-9);
  EXPECT_NEAR(s.odometry_pose.y, 2.6, 1e-9);
  sip.x_raw = 500;
  s = converter.convert(sip, 5.1);
  EXPECT_NEAR(s.odometry_pose.y, 3.1, 1e-9);
}

TEST(ArcosRobot, HandshakesOverAPtyAndReportsTheRobotsIdentity) {
  ArcosPtyServer server(firmware());
  IoThread io;
  auto opened = ArcosRobot::open(io, urlOf(server.url()), pioneer("p3dx"));
  ASSERT_TRUE(opened.robot) << opened.error;
  ArcosRobot& robot = *opened.robot;
  std::vector<TelemetrySample> samples;
  ASSERT_TRUE(waitFor(
      robot, samples, [&] { return robot.linkState() == LinkState::kConnected; }, 10.0));
  ASSERT_TRUE(robot.identity().has_value());
  EXPECT_EQ(*robot.identity(), (arcos::RobotIdentity{"irgs-robot", "Pioneer", "p3dx-sh"}));
  EXPECT_NE(robot.describe().find("irgs-robot Pioneer p3dx-sh"), std::string::npos);
  bool console_has_identity = false;
  for (const auto& e : robot.takeEvents())
    console_has_identity |= e.text.find("p3dx-sh") != std::string::npos;
  EXPECT_TRUE(console_has_identity);

  samples.clear();
  ASSERT_TRUE(waitFor(
      robot, samples, [&] { return samples.size() >= 20; }, 10.0));
  std::size_t readings = 0;
  for (const auto& s : samples)
    readings += s.sonar.size();
  EXPECT_GT(readings, 20u);
  EXPECT_NEAR(samples.back().odometry_pose.x, 0.0, 1e-9);
  const LinkStats stats = robot.linkStats();
  EXPECT_EQ(stats.crc_errors, 0u);
  // Rates for the link-health panel: ~10 SIPs/s of tens of bytes each, PULSEs the other way.
  EXPECT_GT(stats.rx_messages_per_s, 5.0);
  EXPECT_LT(stats.rx_messages_per_s, 15.0);
  EXPECT_GT(stats.rx_bytes_per_s, 100.0);
  EXPECT_GT(stats.tx_bytes_per_s, 0.0);
}

TEST(ArcosRobot, DrivesTheVirtualPioneerAndItsSamplesFollow) {
  ArcosPtyServer server(firmware());
  IoThread io;
  auto opened = ArcosRobot::open(io, urlOf(server.url()), pioneer("p3dx"));
  ASSERT_TRUE(opened.robot) << opened.error;
  ArcosRobot& robot = *opened.robot;
  std::vector<TelemetrySample> samples;
  ASSERT_TRUE(waitFor(
      robot, samples, [&] { return robot.linkState() == LinkState::kConnected; }, 10.0));
  // Asked for again at every 10 ms poll, as a host behaviour answering every sample would.
  ASSERT_TRUE(waitFor(
      robot, samples,
      [&] {
        robot.drive({0.3, 0.0});
        return !samples.empty() && samples.back().odometry_pose.x > 1.0;
      },
      10.0));
  // Beyond the 2 s watchdog: the keep-alive (the VEL and RVEL re-sent in turn) kept it going,
  // and the strict robot lost nothing.
  EXPECT_EQ(server.stats().watchdog_stops, 0u);
  EXPECT_EQ(server.stats().too_soon, 0u);
  EXPECT_EQ(server.stats().bad_commands, 0u);
  EXPECT_LE(server.stats().peak_commands_per_s, 10u);
  EXPECT_NEAR(samples.back().measured_velocity.linear_mps, 0.3, 0.01);
  EXPECT_NEAR(samples.back().odometry_pose.x, server.reportedPose().x, 0.1);
  robot.stop();
  ASSERT_TRUE(waitFor(
      robot, samples, [&] { return std::abs(samples.back().measured_velocity.linear_mps) < 1e-3; },
      5.0));
  EXPECT_EQ(server.trueVelocity().linear_mps, 0.0);
}

TEST(ArcosRobot, TheRobotStopsByItselfWhenPulsesStop) {
  ArcosPtyServer server(firmware());
  IoThread io;
  ArcosRobotConfig config;
  // A ground station that went silent after one VEL: no keep-alive at all.
  config.session.commands.keepalive_s = 1000.0;
  config.session.commands.refresh_s = 1000.0;
  auto opened = ArcosRobot::open(io, urlOf(server.url()), pioneer("p3dx"), config);
  ASSERT_TRUE(opened.robot) << opened.error;
  ArcosRobot& robot = *opened.robot;
  std::vector<TelemetrySample> samples;
  ASSERT_TRUE(waitFor(
      robot, samples, [&] { return robot.linkState() == LinkState::kConnected; }, 10.0));
  robot.drive({0.3, 0.0});
  ASSERT_TRUE(waitFor(
      robot, samples, [&] { return server.trueVelocity().linear_mps > 0.2; }, 5.0));
  const auto moving_since = Clock::now();
  ASSERT_TRUE(waitFor(
      robot, samples, [&] { return server.stats().watchdog_stops == 1; }, 5.0));
  const double stopped_after = std::chrono::duration<double>(Clock::now() - moving_since).count();
  EXPECT_GT(stopped_after, 0.5);  // the 2 s watchdog counts from the VEL, ~1 s before
  EXPECT_LT(stopped_after, 2.5);
  EXPECT_TRUE(waitFor(
      robot, samples, [&] { return server.trueVelocity().linear_mps == 0.0; }, 0.5));
}

TEST(ArcosRobot, ReconnectsWhenTheRobotComesBackOnTheSamePath) {
  const std::filesystem::path link =
      std::filesystem::temp_directory_path() / ("irgs_arcos_" + std::to_string(::getpid()));
  auto server = std::make_unique<ArcosPtyServer>(firmware(), link);
  IoThread io;
  ArcosRobotConfig config;
  config.session.sip_timeout_s = 0.5;
  auto opened = ArcosRobot::open(io, urlOf(server->url()), pioneer("p3dx"), config);
  ASSERT_TRUE(opened.robot) << opened.error;
  ArcosRobot& robot = *opened.robot;
  std::vector<TelemetrySample> samples;
  ASSERT_TRUE(waitFor(
      robot, samples, [&] { return robot.linkState() == LinkState::kConnected; }, 10.0));
  robot.drive({0.2, 0.0});
  server.reset();  // the robot vanishes
  ASSERT_TRUE(waitFor(
      robot, samples, [&] { return robot.linkState() == LinkState::kLost; }, 5.0));
  bool cleared = false;
  for (const auto& e : robot.takeEvents())
    cleared |= e.text.find("command is cleared") != std::string::npos;
  EXPECT_TRUE(cleared);
  server = std::make_unique<ArcosPtyServer>(firmware(), link);
  ASSERT_TRUE(waitFor(
      robot, samples, [&] { return robot.linkState() == LinkState::kConnected; }, 15.0));
  EXPECT_GE(robot.linkStats().link_losses, 1u);
  // The old command was not resumed.
  samples.clear();
  ASSERT_TRUE(waitFor(
      robot, samples, [&] { return samples.size() >= 10; }, 5.0));
  EXPECT_EQ(server->trueVelocity().linear_mps, 0.0);
  server.reset();
  opened.robot.reset();
  std::error_code ec;
  std::filesystem::remove(link, ec);
}

}  // namespace
}  // namespace irgs::comms
