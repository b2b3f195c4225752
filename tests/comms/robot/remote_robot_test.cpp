// RemoteRobot, the one type the GUI and irgs-sim see a linked robot through: the pure clock
// and rate pieces on literal time stamps, then both protocols over a real pty pair (the virtual
// IRGS firmware for MAVLink, the virtual Pioneer for ARCOS) opened by the same call and reached
// through the Robot capability, never a cast.

#include "comms/robot/remote_robot.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <functional>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "comms/robot/robot_clock.hpp"
#include "comms/robot/telemetry_rates.hpp"
#include "comms/transport/io_thread.hpp"
#include "core/sim/sim_presets.hpp"
#include "tests/comms/robot/arcos_pty_server.hpp"
#include "tests/comms/robot/firmware_pty_server.hpp"
#include "tests/comms/robot/robot_test_support.hpp"

namespace irgs::comms {
namespace {

using Clock = std::chrono::steady_clock;

TEST(RobotClock, StartsAtZeroWithTheFirstSampleAndFollowsTheRobotsSteps) {
  RobotClock clock;
  EXPECT_FALSE(clock.started());
  EXPECT_DOUBLE_EQ(clock.sampleTime(100.0), 0.0);
  EXPECT_TRUE(clock.started());
  EXPECT_NEAR(clock.sampleTime(100.05), 0.05, 1e-12);
  EXPECT_NEAR(clock.sampleTime(100.25), 0.25, 1e-12);
  EXPECT_FALSE(clock.restarted());
}

TEST(RobotClock, ARebootContinuesTheClockInsteadOfRunningItBackwards) {
  RobotClock clock;
  clock.sampleTime(100.0);
  clock.sampleTime(100.2);
  EXPECT_NEAR(clock.sampleTime(99.8), 0.2, 1e-12);  // 0.4 s back: late, not a reboot
  EXPECT_FALSE(clock.restarted());
  EXPECT_NEAR(clock.sampleTime(0.3), 0.2 + RobotClock::kRestartStep_s, 1e-12);  // rebooted
  EXPECT_TRUE(clock.restarted());
  EXPECT_NEAR(clock.sampleTime(0.4), 0.35, 1e-12);
  EXPECT_FALSE(clock.restarted());
}

TEST(RobotClock, PutsOtherTimeStampsOnTheSampleClockAndDropsThoseOfAnUnseenReboot) {
  RobotClock clock;
  EXPECT_FALSE(clock.otherTime(5.0).has_value());  // no sample yet: no offset
  clock.sampleTime(100.0);
  EXPECT_DOUBLE_EQ(*clock.otherTime(99.7), 0.0);  // stamped before the first sample: never < 0
  clock.sampleTime(101.0);
  EXPECT_NEAR(*clock.otherTime(101.02), 1.02, 1e-12);
  EXPECT_NEAR(*clock.otherTime(100.6), 0.6, 1e-12);
  EXPECT_FALSE(clock.otherTime(0.2).has_value());  // after a reboot no sample has shown yet
}

TEST(TelemetryRateMeter, MeasuresTheLastThreeSecondsOfTheRobotsClock) {
  TelemetryRateMeter meter;
  // 5 s at 20 Hz; every other sample carries two sonar readings.
  for (int i = 0; i <= 100; ++i)
    meter.add(10.0 + 0.05 * i, i % 2 == 0 ? 2 : 0);
  const TelemetryRates rates = meter.rates();
  EXPECT_NEAR(rates.odometry_hz, 20.0, 1e-9);
  EXPECT_NEAR(rates.sonar_hz, 10.0, 1e-9);
  EXPECT_NEAR(rates.sonar_readings_per_s, 20.0, 1e-9);
  EXPECT_EQ(rates.samples, 101u);
  EXPECT_EQ(rates.sonar_readings, 102u);
}

TEST(TelemetryRateMeter, ARestartEmptiesTheWindowAndKeepsTheTotals) {
  TelemetryRateMeter meter;
  for (int i = 0; i < 10; ++i)
    meter.add(50.0 + 0.1 * i, 1);
  meter.restart();
  meter.add(0.1, 1);
  const TelemetryRates rates = meter.rates();
  EXPECT_EQ(rates.odometry_hz, 0.0);  // one sample spans no time
  EXPECT_EQ(rates.samples, 11u);
  EXPECT_EQ(rates.sonar_readings, 11u);
}

// Room enough to drive a Pioneer straight for a few metres from the origin.
WorldMap room() {
  WorldMap map;
  Wall box;
  box.id = "box";
  box.points = {Vec2(-3, -3), Vec2(6, -3), Vec2(6, 3), Vec2(-3, 3)};
  box.closed = true;
  map.walls.push_back(box);
  return map;
}

LinkUrl urlOf(const std::string& text) {
  auto parsed = parseLinkUrl(text);
  if (!parsed.url)
    throw std::runtime_error(parsed.error);
  return *parsed.url;
}

// Drains `robot` like the GUI (60 Hz) until `done` holds or `timeout_s` passes (a deadline, not
// a sleep the result depends on).
bool drainUntil(Robot& robot, std::vector<TelemetrySample>& samples,
                const std::function<bool()>& done, double timeout_s = 10.0) {
  const auto t0 = Clock::now();
  while (std::chrono::duration<double>(Clock::now() - t0).count() < timeout_s) {
    for (auto& s : robot.update(0.016))
      samples.push_back(std::move(s));
    if (done())
      return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(16));
  }
  return false;
}

std::unique_ptr<RemoteRobot> open(std::shared_ptr<IoThread> io, const std::string& url,
                                  const RobotProfile& profile, RemoteRobotConfig config = {}) {
  OpenRemoteRobotResult opened = openRemoteRobot(std::move(io), urlOf(url), profile, config);
  if (!opened.robot)
    throw std::runtime_error(opened.error);
  return std::move(opened.robot);
}

TEST(RemoteRobot, AMavlinkRobotHasAllThreeLinkCapabilitiesAndItsClockStartsAtZero) {
  testing::FirmwarePtyServer server(testing::makeFirmware({}, true), {});
  auto io = std::make_shared<IoThread>();
  RemoteRobotConfig config;
  config.mavlink.messages.max_rate_hz = 25.0;
  std::unique_ptr<RemoteRobot> remote = open(io, server.url(), testing::thesisRobot(), config);
  Robot& robot = *remote;  // what the session holds
  ASSERT_EQ(robot.remoteRobot(), remote.get());
  EXPECT_EQ(robot.simulationControl(), nullptr);
  EXPECT_EQ(robot.simulatedWorld(), nullptr);
  EXPECT_EQ(remote->protocol(), "mavlink");
  EXPECT_EQ(remote->url(), urlOf(server.url()).toString());
  EXPECT_EQ(remote->linkLabel(), remote->url());
  EXPECT_NE(remote->firmwareParameters(), nullptr);
  EXPECT_NE(remote->messageStream(), nullptr);
  EXPECT_NE(remote->behaviourCommands(), nullptr);

  // The robot has been running since the server started: its boot clock is past zero, ours
  // starts there.
  std::vector<TelemetrySample> samples;
  ASSERT_TRUE(drainUntil(robot, samples, [&] {
    return remote->linkState() == LinkState::kConnected && samples.size() > 70;
  }));
  EXPECT_DOUBLE_EQ(samples.front().time_s, 0.0);
  for (std::size_t i = 1; i < samples.size(); ++i)
    EXPECT_GE(samples[i].time_s, samples[i - 1].time_s);
  const TelemetryRates rates = remote->telemetryRates();
  EXPECT_EQ(rates.samples, samples.size());
  EXPECT_NEAR(rates.odometry_hz, 20.0, 1.0) << "the firmware's odometry rate, robot clock";
  EXPECT_GT(rates.sonar_readings_per_s, 20.0);

  // Messages land on the samples' clock.
  const std::vector<MessageSample> messages = remote->messageStream()->takeMessages();
  ASSERT_FALSE(messages.empty());
  for (const MessageSample& m : messages) {
    EXPECT_GE(m.robot_time_s, 0.0);
    EXPECT_LE(m.robot_time_s, samples.back().time_s + 1.0) << m.message->name;
  }

  // The final stop is confirmed by IRGS_STOP's acknowledgement.
  robot.drive({0.2, 0.0});
  ASSERT_TRUE(drainUntil(robot, samples,
                         [&] { return samples.back().measured_velocity.linear_mps > 0.15; }));
  EXPECT_FALSE(remote->stopConfirmed().has_value());
  remote->requestConfirmedStop();
  ASSERT_TRUE(drainUntil(robot, samples, [&] { return remote->stopConfirmed().has_value(); }));
  EXPECT_TRUE(*remote->stopConfirmed());
  ASSERT_TRUE(drainUntil(robot, samples,
                         [&] { return samples.back().measured_velocity.linear_mps == 0.0; }));
}

TEST(RemoteRobot, AnArcosRobotHasNoneOfTheMavlinkCapabilitiesAndASipAtRestConfirmsItsStop) {
  testing::ArcosPtyServer server(std::make_unique<app::ArcosFirmware>(
      Simulator(room(), testing::robotProfile("pioneer_p3dx.json"), idealSimConfig(SimConfig{})),
      app::ArcosFirmwareConfig{}));
  auto io = std::make_shared<IoThread>();
  RemoteRobotConfig config;
  config.name = "pioneer on a pty";
  std::unique_ptr<RemoteRobot> remote =
      open(io, server.url(), testing::robotProfile("pioneer_p3dx.json"), config);
  io.reset();  // the robot keeps its io thread alive
  Robot& robot = *remote;
  ASSERT_EQ(robot.remoteRobot(), remote.get());
  EXPECT_EQ(remote->protocol(), "arcos");
  EXPECT_EQ(remote->url(), "pioneer on a pty");
  EXPECT_EQ(remote->firmwareParameters(), nullptr);
  EXPECT_EQ(remote->messageStream(), nullptr);
  EXPECT_EQ(remote->behaviourCommands(), nullptr);

  std::vector<TelemetrySample> samples;
  ASSERT_TRUE(drainUntil(robot, samples, [&] {
    return remote->linkState() == LinkState::kConnected && samples.size() > 35;
  }));
  // The panel names the robot the handshake announced.
  EXPECT_NE(remote->linkLabel().find("irgs-robot Pioneer p3dx-sh"), std::string::npos)
      << remote->linkLabel();
  const TelemetryRates rates = remote->telemetryRates();
  EXPECT_NEAR(rates.odometry_hz, 10.0, 1.5) << "one standard SIP per 100 ms";
  EXPECT_EQ(rates.samples, samples.size());

  robot.drive({0.3, 0.0});
  ASSERT_TRUE(drainUntil(robot, samples,
                         [&] { return samples.back().measured_velocity.linear_mps > 0.25; }));
  remote->requestConfirmedStop();
  EXPECT_FALSE(remote->stopConfirmed().has_value()) << "no SIP at rest yet";
  ASSERT_TRUE(drainUntil(robot, samples, [&] { return remote->stopConfirmed().has_value(); }));
  EXPECT_TRUE(*remote->stopConfirmed());
  EXPECT_LT(std::abs(samples.back().measured_velocity.linear_mps), 1e-3);
  EXPECT_EQ(server.trueVelocity().linear_mps, 0.0);
}

TEST(RemoteRobot, ABadConfigurationIsAnErrorAndNoRobot) {
  auto io = std::make_shared<IoThread>();
  RemoteRobotConfig config;
  config.mavlink.teleop_period_s = 0.0;
  OpenRemoteRobotResult opened =
      openRemoteRobot(io, urlOf("tcp://127.0.0.1:9"), testing::thesisRobot(), config);
  EXPECT_EQ(opened.robot, nullptr);
  EXPECT_NE(opened.error.find("teleop_period_s"), std::string::npos) << opened.error;
}

}  // namespace
}  // namespace irgs::comms
