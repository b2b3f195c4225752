// End to end: the irgs-robot executable serving ARCOS (`--protocol arcos --strict --tcp 0` with
// the P3-DX profile on the bundled default map) driven by ArcosRobot over loopback TCP as the
// ground station drives a Pioneer: the sonar grid grows while it turns, and the robot stops by
// itself when the ground station stops sending (PULSE watchdog). Every wait has a deadline; the
// child is always reaped.

#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "comms/robot/arcos_robot.hpp"
#include "comms/transport/io_thread.hpp"
#include "core/mapping/occupancy_grid.hpp"
#include "core/mapping/sonar_mapper.hpp"
#include "core/robot/robot_profile_file.hpp"

namespace {

using Clock = std::chrono::steady_clock;

double since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// The child process with its stdout on a pipe; killed and reaped on destruction.
class Child {
 public:
  explicit Child(const std::vector<std::string>& args) {
    int out[2];
    if (::pipe(out) != 0)
      return;
    pid_ = ::fork();
    if (pid_ == 0) {
      ::dup2(out[1], STDOUT_FILENO);
      ::close(out[0]);
      ::close(out[1]);
      std::vector<char*> argv;
      for (const auto& a : args)
        argv.push_back(const_cast<char*>(a.c_str()));
      argv.push_back(nullptr);
      ::execv(argv[0], argv.data());
      ::_exit(127);
    }
    ::close(out[1]);
    stdout_ = out[0];
  }
  ~Child() {
    if (pid_ > 0) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
    if (stdout_ >= 0)
      ::close(stdout_);
  }
  std::optional<std::string> readLine(double timeout_s) {
    std::string line;
    const auto t0 = Clock::now();
    while (since(t0) < timeout_s) {
      pollfd p{stdout_, POLLIN, 0};
      if (::poll(&p, 1, 50) <= 0)
        continue;
      char c = 0;
      if (::read(stdout_, &c, 1) != 1)
        return std::nullopt;
      if (c == '\n')
        return line;
      line += c;
    }
    return std::nullopt;
  }

 private:
  pid_t pid_ = -1;
  int stdout_ = -1;
};

TEST(ArcosEndToEnd, SonarGridGrowsAndTheRobotStopsWhenPulsesStop) {
  const std::string profile_path =
      std::string(IRGS_SOURCE_DIR) + "/resources/robots/pioneer_p3dx.json";
  Child child({IRGS_ROBOT_EXE, "--protocol", "arcos", "--strict", "--robot", profile_path, "--tcp",
               "0", "--seed", "3"});
  const auto line = child.readLine(20.0);
  ASSERT_TRUE(line.has_value()) << "irgs-robot printed no port";
  ASSERT_EQ(line->rfind("tcp ", 0), 0u) << *line;
  const std::string url_text = "tcp://127.0.0.1:" + line->substr(4) + "?protocol=arcos";

  auto profile = irgs::loadRobotProfileFile(profile_path);
  ASSERT_TRUE(profile.profile);
  irgs::comms::IoThread io;
  irgs::comms::ArcosRobotConfig config;
  // The test plays the ground station's keep-alive itself: no PULSE and no refresh, and every
  // drive() below is a change (45 and 46 deg/s in turn), which goes out at once; so when it stops
  // calling drive() the robot hears nothing.
  config.session.commands.keepalive_s = 1000.0;
  config.session.commands.refresh_s = 1000.0;
  config.session.sip_timeout_s = 5.0;
  auto parsed = irgs::comms::parseLinkUrl(url_text);
  ASSERT_TRUE(parsed.url) << parsed.error;
  auto opened = irgs::comms::ArcosRobot::open(io, *parsed.url, *profile.profile, config);
  ASSERT_TRUE(opened.robot) << opened.error;
  irgs::comms::ArcosRobot& robot = *opened.robot;

  const irgs::SonarMapper mapper(*profile.profile);
  irgs::OccupancyGrid grid(0.05);
  std::vector<irgs::TelemetrySample> last;
  auto drain = [&] {
    for (auto& s : robot.update(0.0)) {
      mapper.integrate(s, grid);
      last.assign(1, s);
    }
  };
  auto t0 = Clock::now();
  while (robot.linkState() != irgs::comms::LinkState::kConnected || last.empty()) {
    ASSERT_LT(since(t0), 15.0) << "no ARCOS connection to " << url_text;
    drain();
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ASSERT_TRUE(robot.identity());
  EXPECT_EQ(robot.identity()->subclass, "p3dx-sh");

  // Turn in place for 4 s, refreshing the command every 0.5 s (inside the 2 s watchdog).
  const std::uint64_t cells_at_start = grid.observedCellCount();
  t0 = Clock::now();
  double next_drive = 0.0;
  int drives = 0;
  while (since(t0) < 4.0) {
    if (since(t0) >= next_drive) {
      robot.drive({0.0, irgs::degToRad(drives++ % 2 == 0 ? 45.0 : 46.0)});
      next_drive += 0.5;
    }
    drain();
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ASSERT_FALSE(last.empty());
  EXPECT_GT(std::abs(last.back().measured_velocity.angular_radps), irgs::degToRad(30.0));
  EXPECT_GT(grid.observedCellCount(), cells_at_start + 200) << "the sonar grid did not grow";

  // Silence: within the 2 s watchdog (+ a SIP period and margin) the robot reports standstill.
  const auto silent_since = Clock::now();
  std::optional<double> stopped_after;
  while (since(silent_since) < 4.0) {
    drain();
    if (!last.empty() && std::abs(last.back().measured_velocity.angular_radps) < 1e-3) {
      stopped_after = since(silent_since);
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ASSERT_TRUE(stopped_after.has_value()) << "the robot kept turning without PULSEs";
  EXPECT_GT(*stopped_after, 1.0);  // not before the watchdog (last VEL <= 0.5 s before)
  EXPECT_LT(*stopped_after, 3.0);
}

}  // namespace
