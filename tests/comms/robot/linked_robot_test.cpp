// LinkedRobot end to end over a real pty pair at 115200 baud (paced like a UART): the virtual
// robot firmware (FirmwareCore) runs in-process on the master side, LinkedRobot opens the slave
// as serial://. Every wait is a polling loop on a condition with a generous deadline (the GUI's
// 60 Hz drain), never a fixed sleep that decides the outcome.

#include "comms/robot/linked_robot.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <future>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "comms/transport/io_thread.hpp"
#include "tests/comms/robot/firmware_pty_server.hpp"
#include "tests/comms/robot/robot_test_support.hpp"

namespace irgs::comms {
namespace {

using namespace std::chrono_literals;
using testing::FirmwarePtyServer;

constexpr auto kDeadline = 10s;  // only reached when a test fails

LinkUrl urlOf(const std::string& text) {
  auto parsed = parseLinkUrl(text);
  if (!parsed.url)
    throw std::invalid_argument(parsed.error);
  return *parsed.url;
}

// Quick reconnection so the tests stay short. The loss timeout stays at its default (1.5 s):
// the firmware sends its heartbeat at 1 Hz.
LinkedRobotConfig fastConfig() {
  LinkedRobotConfig c;
  c.link.tick_s = 0.02;
  c.link.reconnect_initial_s = 0.05;
  c.link.reconnect_max_s = 0.2;
  c.link.session.heartbeat_period_s = 0.2;
  c.link.session.commands.retry_s = 0.2;
  return c;
}

// Drains the robot like the GUI does (update() at 60 Hz) and keeps everything it got.
class Drain {
 public:
  explicit Drain(LinkedRobot& robot) : robot_(robot) {}

  // Drains until `done()` holds or the deadline passes; returns done().
  bool until(const std::function<bool()>& done,
             std::chrono::steady_clock::duration limit = kDeadline) {
    const auto deadline = std::chrono::steady_clock::now() + limit;
    while (!done()) {
      if (std::chrono::steady_clock::now() > deadline)
        return false;
      std::this_thread::sleep_for(16ms);
      once();
    }
    return true;
  }
  void once() {
    for (auto& s : robot_.update(0.016))
      samples.push_back(std::move(s));
    for (auto& e : robot_.takeEvents())
      events.push_back(std::move(e));
  }
  std::size_t count(LinkEventKind kind) const {
    return static_cast<std::size_t>(std::count_if(
        events.begin(), events.end(), [&](const LinkEvent& e) { return e.kind == kind; }));
  }
  bool hasEvent(LinkEventKind kind, const std::string& text) const {
    return std::any_of(events.begin(), events.end(), [&](const LinkEvent& e) {
      return e.kind == kind && e.text.find(text) != std::string::npos;
    });
  }
  std::string dump() const {
    std::string out;
    for (const auto& e : events)
      out += std::string(toString(e.kind)) + ": " + e.text + "\n";
    return out;
  }

  std::vector<TelemetrySample> samples;
  std::vector<LinkEvent> events;

 private:
  LinkedRobot& robot_;
};

std::unique_ptr<LinkedRobot> openRobot(IoThread& io, const std::string& url,
                                       LinkedRobotConfig config = fastConfig()) {
  auto opened = LinkedRobot::open(io, urlOf(url), testing::thesisRobot(), config);
  if (!opened.robot)
    throw std::runtime_error(opened.error);
  return std::move(opened.robot);
}

TEST(LinkedRobot, StreamsTheFirmwareOdometryAtTwentyHertzWithSonarFromTheRightSensors) {
  FirmwarePtyServer server(testing::makeFirmware({}, true), {});
  IoThread io;
  auto robot = openRobot(io, server.url());
  Drain drain(*robot);
  ASSERT_TRUE(drain.until([&] { return robot->linkState() == LinkState::kConnected; }))
      << drain.dump();
  EXPECT_NE(robot->describe().find(server.slavePath()), std::string::npos) << robot->describe();
  EXPECT_NE(robot->describe().find("connected"), std::string::npos) << robot->describe();

  // Forward and turning counter-clockwise for 2 s of samples (well past the firmware's 0.3 s
  // teleop expiry: the command must be repeated).
  robot->drive({0.2, 0.4});
  // From the second sample on: the first may carry readings whose own pose went by before the
  // port was opened (they ride on the next pose, as documented).
  const std::size_t first = std::max<std::size_t>(1, drain.samples.size());
  ASSERT_TRUE(drain.until([&] {
    return drain.samples.size() > first &&
           drain.samples.back().time_s - drain.samples[first].time_s >= 2.0;
  }));
  const auto& s = drain.samples;
  const double span = s.back().time_s - s[first].time_s;
  const double rate = static_cast<double>(s.size() - first - 1) / span;
  EXPECT_GE(rate, 19.5) << "odometry rate on the robot's clock";

  // Poses equal the firmware's odometry at the same step (float precision on the wire).
  std::size_t compared = 0;
  std::set<int> sensors;
  std::size_t readings = 0;
  for (std::size_t i = first; i < s.size(); ++i) {
    const auto ms = std::llround(s[i].time_s * 1000.0);
    const auto truth = server.odometryAt(ms);
    ASSERT_TRUE(truth.has_value()) << ms;
    EXPECT_NEAR(s[i].odometry_pose.x, truth->x, 2e-6);
    EXPECT_NEAR(s[i].odometry_pose.y, truth->y, 2e-6);
    EXPECT_NEAR(wrapAngle(s[i].odometry_pose.theta - truth->theta), 0.0, 2e-6);
    ++compared;
    // The sonar readings are exactly the DISTANCE_SENSOR frames of that step, index for index.
    const auto frames = server.sonarAt(ms);
    ASSERT_EQ(s[i].sonar.size(), frames.size()) << ms;
    for (std::size_t k = 0; k < frames.size(); ++k) {
      EXPECT_EQ(s[i].sonar[k].sensor, frames[k].sensor);
      EXPECT_EQ(s[i].sonar[k].echo, frames[k].distance_cm <= frames[k].max_cm);
      if (s[i].sonar[k].echo) {
        EXPECT_NEAR(s[i].sonar[k].range_m, frames[k].distance_cm * 0.01, 1e-12);
      }
      sensors.insert(s[i].sonar[k].sensor);
      ++readings;
    }
  }
  EXPECT_GE(compared, 40u);
  EXPECT_EQ(sensors.size(), testing::thesisRobot().sonars.size()) << "every sonar reported";
  EXPECT_GE(static_cast<double>(readings) / span, 20.0) << "sonar readings per second";

  // It drove: forward and counter-clockwise, and kept moving (MANUAL_CONTROL repeated).
  EXPECT_GT(std::hypot(s.back().odometry_pose.x - s[first].odometry_pose.x,
                       s.back().odometry_pose.y - s[first].odometry_pose.y),
            0.2);
  EXPECT_GT(wrapAngle(s.back().odometry_pose.theta - s[first].odometry_pose.theta), 0.3);
  const auto moving_from =
      std::find_if(s.begin() + static_cast<std::ptrdiff_t>(first), s.end(),
                   [](const auto& x) { return x.measured_velocity.linear_mps > 0.15; });
  ASSERT_NE(moving_from, s.end());
  for (auto it = moving_from; it != s.end(); ++it)
    EXPECT_GT(it->measured_velocity.linear_mps, 0.1)
        << "stopped at " << it->time_s << " bumpers " << it->bumpers << "\n"
        << drain.dump();
  EXPECT_EQ(robot->droppedSamples(), 0u);
}

TEST(LinkedRobot, HandsOnEveryFieldOfTheRobotsMessagesWhenAskedTo) {
  FirmwarePtyServer server(testing::makeFirmware({}, true), {});
  IoThread io;
  LinkedRobotConfig config = fastConfig();
  config.messages.max_rate_hz = 25.0;
  auto robot = openRobot(io, server.url(), config);
  Drain drain(*robot);
  std::vector<MessageSample> messages;
  std::set<std::uint32_t> sonars;
  ASSERT_TRUE(drain.until([&] {
    for (auto& m : robot->takeMessages())
      messages.push_back(std::move(m));
    sonars.clear();
    for (const MessageSample& m : messages) {
      if (m.message->name == "DISTANCE_SENSOR")
        sonars.insert(*m.instance);
    }
    return messages.size() > 200 && sonars.size() == testing::thesisRobot().sonars.size();
  })) << messages.size()
      << " messages, " << sonars.size() << " sonars";
  // LOCAL_POSITION_NED x is the firmware's odometry x at the message's own time stamp.
  std::size_t compared = 0;
  for (const MessageSample& m : messages) {
    ASSERT_EQ(m.values.size(), m.message->fields.size());
    if (m.message->name != "LOCAL_POSITION_NED")
      continue;
    ASSERT_EQ(m.message->fields[1].name, "x");
    const auto ms = std::llround(m.robot_time_s * 1000.0);
    EXPECT_EQ(static_cast<double>(ms), m.values[0]);  // time_boot_ms
    if (const auto truth = server.odometryAt(ms)) {
      EXPECT_NEAR(m.values[1], truth->x, 2e-6);
      ++compared;
    }
  }
  EXPECT_GE(compared, 5u);
  EXPECT_EQ(robot->messageCounters().dropped, 0u);
}

TEST(LinkedRobot, HandsOnNoMessagesByDefault) {
  FirmwarePtyServer server(testing::makeFirmware({}, true), {});
  IoThread io;
  auto robot = openRobot(io, server.url());
  Drain drain(*robot);
  ASSERT_TRUE(drain.until([&] { return drain.samples.size() > 10; }));
  EXPECT_TRUE(robot->takeMessages().empty());
  EXPECT_EQ(robot->messageCounters().kept, 0u);
}

TEST(LinkedRobot, StopBrakesTheRobotAndReportsTheAcknowledgedStop) {
  FirmwarePtyServer server(testing::makeFirmware({}, true), {});
  IoThread io;
  auto robot = openRobot(io, server.url());
  Drain drain(*robot);
  ASSERT_TRUE(drain.until([&] { return robot->linkState() == LinkState::kConnected; }));
  robot->drive({0.3, 0.0});
  ASSERT_TRUE(drain.until([&] {
    return !drain.samples.empty() && drain.samples.back().measured_velocity.linear_mps > 0.25;
  }));
  const double stop_sent_robot_s = drain.samples.back().time_s;
  robot->stop();
  ASSERT_TRUE(drain.until([&] {
    return drain.samples.back().measured_velocity.linear_mps == 0.0 &&
           drain.hasEvent(LinkEventKind::kCommandResult, "IRGS_STOP accepted") &&
           drain.hasEvent(LinkEventKind::kStatusText, "stop");
  })) << drain.dump();
  // Controlled stop at the profile's deceleration (0.3 m/s at 0.8 m/s^2 = 0.375 s) plus the
  // link and assembly delays.
  const auto stopped = std::find_if(drain.samples.begin(), drain.samples.end(), [&](const auto& x) {
    return x.time_s > stop_sent_robot_s && x.measured_velocity.linear_mps == 0.0;
  });
  ASSERT_NE(stopped, drain.samples.end());
  EXPECT_LE(stopped->time_s - stop_sent_robot_s, 0.6);
  const auto stopped_index = static_cast<std::size_t>(stopped - drain.samples.begin());
  // And it stays stopped: stop() ended the MANUAL_CONTROL repetition.
  const double settled = drain.samples.back().time_s;
  ASSERT_TRUE(drain.until([&] { return drain.samples.back().time_s > settled + 0.5; }));
  for (std::size_t i = stopped_index; i < drain.samples.size(); ++i)
    EXPECT_EQ(drain.samples[i].measured_velocity.linear_mps, 0.0) << drain.samples[i].time_s;
}

// Issue 24: a behaviour calling drive() every 2 ms with a new command each time (500 changes a
// second; before, each one was a MANUAL_CONTROL) reaches the robot as at most 20 a second, the
// newest command each time, and the robot still stops when told.
TEST(LinkedRobot, ADriveEveryTwoMillisecondsReachesTheRobotAsAtMostTwentyManualControlsASecond) {
  FirmwarePtyServer server(testing::makeFirmware({}, true), {});
  IoThread io;
  auto robot = openRobot(io, server.url());
  Drain drain(*robot);
  ASSERT_TRUE(drain.until([&] { return robot->linkState() == LinkState::kConnected; }));
  const auto start = std::chrono::steady_clock::now();
  const auto elapsed_s = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  for (int i = 0; elapsed_s() < 2.0; ++i) {
    robot->drive({0.2, 0.01 * (i % 50)});  // a new turn rate at every call
    std::this_thread::sleep_for(2ms);
  }
  robot->stop();
  ASSERT_TRUE(drain.until([&] {
    return !drain.samples.empty() && drain.samples.back().measured_velocity.linear_mps == 0.0;
  })) << "the robot did not stop";
  const std::vector<double> arrivals = server.manualControlArrivals();
  std::size_t peak = 0;
  for (std::size_t i = 0; i < arrivals.size(); ++i) {
    const auto end = std::lower_bound(arrivals.begin() + static_cast<std::ptrdiff_t>(i),
                                      arrivals.end(), arrivals[i] + 1.0);
    peak = std::max(peak, static_cast<std::size_t>(end - arrivals.begin()) - i);
  }
  std::printf("MANUAL_CONTROL on the wire: %zu in %.1f s, peak %zu in 1 s\n", arrivals.size(),
              arrivals.empty() ? 0.0 : arrivals.back() - arrivals.front(), peak);
  EXPECT_LE(peak, 20u);
  EXPECT_GE(peak, 15u) << "the changes did not get through";
  EXPECT_GE(arrivals.size(), 30u);
}

TEST(LinkedRobot, MoveDistanceBehaviourIsAcknowledgedAndDrivesTheDistance) {
  FirmwarePtyServer server(testing::makeFirmware({}, true), {});
  IoThread io;
  auto robot = openRobot(io, server.url());
  Drain drain(*robot);
  ASSERT_TRUE(drain.until(
      [&] { return robot->linkState() == LinkState::kConnected && !drain.samples.empty(); }));
  const Pose2 start = drain.samples.back().odometry_pose;
  std::promise<CommandResult> result;
  robot->sendBehaviour({.kind = RobotBehaviourKind::kMoveDistance, .distance_m = 0.25},
                       [&result](const CommandResult& r) { result.set_value(r); });
  auto future = result.get_future();
  ASSERT_EQ(future.wait_for(kDeadline), std::future_status::ready);
  EXPECT_EQ(future.get().outcome, CommandOutcome::kAccepted);
  ASSERT_TRUE(drain.until([&] {
    const Pose2& p = drain.samples.back().odometry_pose;
    return std::hypot(p.x - start.x, p.y - start.y) > 0.24 &&
           drain.samples.back().measured_velocity.linear_mps == 0.0;
  })) << drain.dump();
  const Pose2& end = drain.samples.back().odometry_pose;
  EXPECT_NEAR(std::hypot(end.x - start.x, end.y - start.y), 0.25, 0.02);
}

TEST(LinkedRobot, ReportsLinkLossAndReconnectsToARestartedRobot) {
  namespace fs = std::filesystem;
  const fs::path link =
      fs::temp_directory_path() / ("irgs_linked_robot_test_" + std::to_string(::getpid()));
  auto server = std::make_unique<FirmwarePtyServer>(
      testing::makeFirmware({}, true),
      FirmwarePtyServer::Options{.bytes_per_s = 11520.0, .symlink = link});
  IoThread io;
  auto robot = openRobot(io, server->url());
  Drain drain(*robot);
  ASSERT_TRUE(drain.until([&] {
    return drain.count(LinkEventKind::kLinkUp) == 1 && !drain.samples.empty() &&
           drain.samples.back().time_s > 1.2;
  }));
  robot->drive({0.1, 0.0});

  server->stop();  // the robot vanishes (power cut, USB unplugged)
  ASSERT_TRUE(drain.until([&] { return drain.count(LinkEventKind::kLinkLost) >= 1; }))
      << drain.dump();
  EXPECT_NE(robot->linkState(), LinkState::kConnected);
  EXPECT_TRUE(drain.hasEvent(LinkEventKind::kTransport, "teleop command cleared")) << drain.dump();
  const double before_restart_s = drain.samples.back().time_s;
  ASSERT_GT(before_restart_s, 1.2);

  // The robot restarts on the same name: its boot clock starts over.
  server = std::make_unique<FirmwarePtyServer>(
      testing::makeFirmware({}, true),
      FirmwarePtyServer::Options{.bytes_per_s = 11520.0, .symlink = link});
  const std::size_t seen = drain.samples.size();
  ASSERT_TRUE(drain.until([&] {
    return drain.count(LinkEventKind::kLinkUp) >= 2 && drain.samples.size() > seen + 5;
  })) << drain.dump();
  EXPECT_EQ(robot->linkState(), LinkState::kConnected);
  EXPECT_LT(drain.samples.back().time_s, before_restart_s);  // the new boot's clock
  // Samples of the new boot are delivered with the new time base and the firmware's poses.
  const auto& last = drain.samples.back();
  const auto truth = server->odometryAt(std::llround(last.time_s * 1000.0));
  ASSERT_TRUE(truth.has_value());
  EXPECT_NEAR(last.odometry_pose.x, truth->x, 2e-6);
  // The cleared command was not resumed: the restarted robot stands still.
  EXPECT_EQ(last.measured_velocity.linear_mps, 0.0);
  const LinkStats stats = robot->linkStats();
  EXPECT_GE(stats.link_losses, 1u);
  server.reset();
  robot.reset();
  fs::remove(link);
}

TEST(LinkedRobot, OpenReportsBadConfigurationAsAnError) {
  IoThread io;
  LinkedRobotConfig config;
  config.teleop_period_s = 0.0;
  auto opened = LinkedRobot::open(io, urlOf("tcp://127.0.0.1:9"), testing::thesisRobot(), config);
  EXPECT_EQ(opened.robot, nullptr);
  EXPECT_NE(opened.error.find("teleop_period_s"), std::string::npos);
  config = {};
  config.telemetry.hold_s = -1.0;
  opened = LinkedRobot::open(io, urlOf("tcp://127.0.0.1:9"), testing::thesisRobot(), config);
  EXPECT_EQ(opened.robot, nullptr);
  EXPECT_NE(opened.error.find("hold_s"), std::string::npos);
  RobotProfile still = testing::thesisRobot();
  still.limits.max_speed_mps = 0.0;
  opened = LinkedRobot::open(io, urlOf("tcp://127.0.0.1:9"), still, {});
  EXPECT_EQ(opened.robot, nullptr);
}

TEST(LinkedRobot, DriveRejectsANonFiniteCommand) {
  IoThread io;
  auto robot = openRobot(io, "tcp://127.0.0.1:9");
  EXPECT_THROW(robot->drive({std::nan(""), 0.0}), std::invalid_argument);
  EXPECT_NE(robot->describe().find("tcp://127.0.0.1:9"), std::string::npos);
}

}  // namespace
}  // namespace irgs::comms

namespace irgs::comms {
namespace {

// The parameter protocol end to end: read all nine firmware parameters, write one in range
// (the firmware applies it) and one out of range (the firmware keeps its value: rejected).
TEST(LinkedRobot, ReadsAllFirmwareParametersAndWritesOneConfirmed) {
  FirmwarePtyServer server(testing::makeFirmware({}, true), {});
  IoThread io;
  auto robot = openRobot(io, server.url());
  Drain drain(*robot);
  ASSERT_TRUE(drain.until([&] { return robot->linkState() == LinkState::kConnected; }));
  robot->requestParams();
  constexpr auto kCount = static_cast<int>(app::ParamTable::size());
  ASSERT_TRUE(drain.until([&] {
    return robot->firmwareParamCount() == kCount &&
           static_cast<int>(robot->firmwareParams().size()) == kCount && !robot->readingParams();
  }));
  const std::vector<ParamEntry> params = robot->firmwareParams();
  for (int i = 0; i < kCount; ++i) {
    EXPECT_EQ(params[static_cast<std::size_t>(i)].index, i);
    EXPECT_EQ(params[static_cast<std::size_t>(i)].name,
              app::paramSpecs()[static_cast<std::size_t>(i)].name);
  }
  const auto hb = robot->firmwareParams()[static_cast<std::size_t>(app::ParamId::kHbTimeout)];
  EXPECT_FLOAT_EQ(static_cast<float>(hb.value),
                  static_cast<float>(server.params().get(app::ParamId::kHbTimeout)));

  robot->setParam("HB_TIMEOUT", 2.5);
  std::vector<ParamWriteResult> results;
  ASSERT_TRUE(drain.until([&] {
    for (auto& r : robot->takeParamResults())
      results.push_back(r);
    return !results.empty();
  }));
  EXPECT_EQ(results[0].status, ParamWriteStatus::kAccepted);
  EXPECT_DOUBLE_EQ(server.params().get(app::ParamId::kHbTimeout), 2.5);
  EXPECT_DOUBLE_EQ(
      robot->firmwareParams()[static_cast<std::size_t>(app::ParamId::kHbTimeout)].value, 2.5);

  results.clear();
  robot->setParam("TELEOP_TIMEOUT", 5.0);  // outside [0.05, 0.45]
  ASSERT_TRUE(drain.until([&] {
    for (auto& r : robot->takeParamResults())
      results.push_back(r);
    return !results.empty();
  }));
  EXPECT_EQ(results[0].status, ParamWriteStatus::kRejected);
  ASSERT_TRUE(results[0].applied.has_value());
  EXPECT_NEAR(*results[0].applied, server.params().get(app::ParamId::kTeleopTimeout), 1e-6);
  EXPECT_THROW(robot->setParam("A_NAME_LONGER_THAN_16", 1.0), std::invalid_argument);
}

}  // namespace
}  // namespace irgs::comms
