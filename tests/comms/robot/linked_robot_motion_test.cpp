// LinkedRobot's MotionControl end to end: the virtual firmware (FirmwareCore) served on a real
// pty at 115200 baud, LinkedRobot on the slave, primitives run on the firmware to their final
// reports. The host drains like the GUI (update() then takeReports() at 60 Hz); every wait is a
// polling loop on a condition with a deadline only reached when a test fails.

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <thread>
#include <vector>

#include "comms/robot/linked_robot.hpp"
#include "comms/transport/io_thread.hpp"
#include "tests/comms/robot/firmware_pty_server.hpp"
#include "tests/comms/robot/robot_test_support.hpp"

namespace irgs::comms {
namespace {

using namespace std::chrono_literals;
using motion::ReportKind;
using testing::FirmwarePtyServer;

// What the host saw, in the order it saw it.
struct HostLog {
  std::vector<TelemetrySample> samples;
  std::vector<motion::MotionReport> reports;
  // For every report: the newest sample time the host had when it took the report.
  std::vector<double> sample_time_at_report;
};

class MotionHost {
 public:
  explicit MotionHost(const std::string& url) {
    LinkedRobotConfig config;
    config.link.tick_s = 0.02;
    config.link.session.heartbeat_period_s = 0.2;
    auto parsed = parseLinkUrl(url);
    if (!parsed.url)
      throw std::invalid_argument(parsed.error);
    auto opened = LinkedRobot::open(io_, *parsed.url, testing::thesisRobot(), config);
    if (!opened.robot)
      throw std::runtime_error(opened.error);
    robot_ = std::move(opened.robot);
  }

  LinkedRobot& robot() { return *robot_; }
  MotionControl& motion() { return *robot_->motionControl(); }

  // Drains until `done()` holds or `limit` passes; returns done().
  bool until(const std::function<bool()>& done, std::chrono::seconds limit) {
    const auto deadline = std::chrono::steady_clock::now() + limit;
    while (!done()) {
      if (std::chrono::steady_clock::now() > deadline)
        return false;
      std::this_thread::sleep_for(16ms);
      for (auto& s : robot_->update(0.016))
        log.samples.push_back(std::move(s));
      for (auto& r : motion().takeReports()) {
        log.reports.push_back(r);
        log.sample_time_at_report.push_back(log.samples.empty() ? -1.0 : log.samples.back().time_s);
      }
    }
    return true;
  }
  bool finished(std::uint16_t id) const {
    return std::any_of(log.reports.begin(), log.reports.end(),
                       [&](const auto& r) { return r.id == id && motion::isFinal(r.kind); });
  }
  std::vector<motion::MotionReport> reportsOf(std::uint16_t id) const {
    std::vector<motion::MotionReport> out;
    for (const auto& r : log.reports)
      if (r.id == id)
        out.push_back(r);
    return out;
  }
  // The odometry pose of the sample at `time_s` (the robot's clock), if the host got one.
  std::optional<Pose2> poseAt(double time_s) const {
    for (const auto& s : log.samples)
      if (std::abs(s.time_s - time_s) < 1e-6)
        return s.odometry_pose;
    return std::nullopt;
  }

  HostLog log;

 private:
  IoThread io_;
  std::unique_ptr<LinkedRobot> robot_;
};

// Every report after the samples up to its time; kStarted first, one final report, last.
void expectInOrderWithTheSamples(const MotionHost& host, std::uint16_t id) {
  const auto reports = host.reportsOf(id);
  ASSERT_GE(reports.size(), 2u);
  EXPECT_EQ(reports.front().kind, ReportKind::kStarted);
  EXPECT_TRUE(motion::isFinal(reports.back().kind));
  EXPECT_EQ(std::count_if(reports.begin(), reports.end(),
                          [](const auto& r) { return motion::isFinal(r.kind); }),
            1);
  for (std::size_t i = 0; i < host.log.reports.size(); ++i) {
    const auto& r = host.log.reports[i];
    EXPECT_LE(r.time_s, host.log.sample_time_at_report[i] + 1e-9) << toString(r.kind);
    // A report's pose is the firmware's odometry of its step; the sample of that step (when
    // the 20 Hz stream carried one) shows the same pose.
    if (const auto pose = host.poseAt(r.time_s)) {
      EXPECT_NEAR(pose->x, r.pose.x, 1e-4);
      EXPECT_NEAR(pose->y, r.pose.y, 1e-4);
    }
  }
}

TEST(LinkedRobotMotion, FollowsAWallOnTheFirmwareToItsTravelLimit) {
  FirmwarePtyServer server(testing::makeFirmware({}, true), {});
  MotionHost host(server.url());
  ASSERT_TRUE(host.until([&] { return !host.log.samples.empty(); }, 10s));
  EXPECT_TRUE(host.motion().supports(motion::PrimitiveKind::kFollowPath));
  // From the default map's start heading north: seek the wall 1.9 m ahead, turn left with it
  // on the right, follow it west.
  const motion::FollowWallSpec spec{.wall_on_left = false,
                                    .distance_m = 0.35,
                                    .speed_mps = 0.25,
                                    .travel_limit_m = 1.9,
                                    .report_every_m = 0.5};
  host.motion().start({7, spec});
  ASSERT_TRUE(host.until([&] { return host.finished(7); }, 40s));
  expectInOrderWithTheSamples(host, 7);
  const auto reports = host.reportsOf(7);
  EXPECT_EQ(reports.back().kind, ReportKind::kDone);
  EXPECT_NEAR(reports.back().distance_m, 1.9, 0.03);
  const auto marks = std::count_if(reports.begin(), reports.end(), [](const auto& r) {
    return r.kind == ReportKind::kDistanceMark;
  });
  EXPECT_GE(marks, 3);
  EXPECT_TRUE(std::any_of(reports.begin(), reports.end(), [](const auto& r) {
    return r.kind == ReportKind::kMode &&
           r.index == static_cast<int>(motion::WallFollowMode::kTurn);
  }));
  // Following the wall along y = 3.5 at 0.35 m, heading west.
  const Pose2 end = server.truePose();
  EXPECT_NEAR(end.y, 3.5 - 0.35, 0.1);
  EXPECT_NEAR(std::abs(wrapAngle(end.theta - kPi)), 0.0, degToRad(15.0));
}

TEST(LinkedRobotMotion, RunsSegmentsOnTheFirmwareReportingEachTurningPoint) {
  FirmwarePtyServer server(testing::makeFirmware({}, true), {});
  MotionHost host(server.url());
  ASSERT_TRUE(host.until([&] { return !host.log.samples.empty(); }, 10s));
  const Pose2 start = host.log.samples.back().odometry_pose;
  motion::SegmentsSpec spec;
  spec.append(start.position() + Vec2(0.0, 0.6));
  spec.append(start.position() + Vec2(0.6, 0.6));
  spec.append(start.position() + Vec2(0.6, 0.2));
  spec.speed_mps = 0.3;
  host.motion().start({8, spec});
  ASSERT_TRUE(host.until([&] { return host.finished(8); }, 40s));
  expectInOrderWithTheSamples(host, 8);
  const auto reports = host.reportsOf(8);
  std::vector<ReportKind> kinds;
  for (const auto& r : reports)
    kinds.push_back(r.kind);
  EXPECT_EQ(kinds,
            (std::vector{ReportKind::kStarted, ReportKind::kTurningPoint, ReportKind::kTurningPoint,
                         ReportKind::kTurningPoint, ReportKind::kDone}));
  for (std::size_t i = 0; i + 2 < reports.size(); ++i) {
    EXPECT_EQ(reports[i + 1].index, static_cast<int>(i));
    EXPECT_LT((reports[i + 1].pose.position() - spec.points[i]).norm(), 0.02) << i;
  }
  EXPECT_NEAR(reports.back().distance_m, 1.6, 0.03);

  // Cancelled while it runs: the robot stops and the host hears kCancelled.
  motion::SegmentsSpec back;
  back.append(start.position());
  host.motion().start({9, back});
  ASSERT_TRUE(host.until([&] { return host.reportsOf(9).size() == 1; }, 10s));
  host.motion().cancel();
  ASSERT_TRUE(host.until([&] { return host.finished(9); }, 10s));
  EXPECT_EQ(host.reportsOf(9).back().kind, ReportKind::kCancelled);
}

}  // namespace
}  // namespace irgs::comms
