// End to end: start the irgs-robot executable on a pseudo-terminal, act as a minimal ground
// station on the slave side (raw fd, our own FrameEncoder/FrameDecoder), drive it and check the
// telemetry and the teleop-expiry stop. Every wait has a deadline; the child is always reaped.

#include <fcntl.h>
#include <netinet/in.h>
#include <poll.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <termios.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "comms/mavlink/frame_decoder.hpp"
#include "comms/mavlink/frame_encoder.hpp"
#include "comms/mavlink/messages.hpp"

namespace {

namespace mav = irgs::comms::mavlink;
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
    if (pid_ > 0 && !reaped_) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
    if (stdout_ >= 0)
      ::close(stdout_);
  }

  // First line of stdout, or nullopt after `timeout_s`.
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

  // Sends `sig` and waits up to `timeout_s` for the exit; returns the exit status or -1.
  int terminate(int sig, double timeout_s) {
    ::kill(pid_, sig);
    const auto t0 = Clock::now();
    while (since(t0) < timeout_s) {
      int status = 0;
      if (::waitpid(pid_, &status, WNOHANG) == pid_) {
        reaped_ = true;
        return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
      }
      ::usleep(10'000);
    }
    return -1;
  }

  bool started() const { return pid_ > 0; }

 private:
  pid_t pid_ = -1;
  int stdout_ = -1;
  bool reaped_ = false;
};

class Port {
 public:
  explicit Port(const std::string& path) {
    fd_ = ::open(path.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK);
    if (fd_ < 0)
      return;
    termios tio{};
    ::tcgetattr(fd_, &tio);
    ::cfmakeraw(&tio);
    ::tcsetattr(fd_, TCSANOW, &tio);
  }
  ~Port() {
    if (fd_ >= 0)
      ::close(fd_);
  }
  bool ok() const { return fd_ >= 0; }

  template <class M>
  void send(const M& m) {
    const auto frame = encoder_.encode(m);
    ASSERT_EQ(::write(fd_, frame.bytes.data(), frame.size), static_cast<ssize_t>(frame.size));
  }

  // Waits up to `timeout_s` for input and returns the frames decoded from it.
  std::vector<mav::Frame> receive(double timeout_s) {
    std::vector<mav::Frame> frames;
    pollfd p{fd_, POLLIN, 0};
    if (::poll(&p, 1, static_cast<int>(timeout_s * 1000)) <= 0)
      return frames;
    std::uint8_t buf[4096];
    const ssize_t n = ::read(fd_, buf, sizeof buf);
    if (n > 0)
      decoder_.feed(std::span<const std::uint8_t>(buf, static_cast<std::size_t>(n)), frames);
    return frames;
  }
  const mav::DecodeCounters& totals() const { return decoder_.totals(); }

 private:
  int fd_ = -1;
  mav::FrameEncoder encoder_{255, 190};
  mav::FrameDecoder decoder_;
};

struct OdometrySample {
  double robot_s;
  double x;
  double y;
  double vx;
};

TEST(IrgsRobotEndToEnd, DrivesOverAPtyStreamsTelemetryAndStopsWhenTeleopExpires) {
  Child robot({IRGS_ROBOT_EXE, "--ideal", "--seed", "3"});
  ASSERT_TRUE(robot.started());
  const auto path = robot.readLine(20.0);
  ASSERT_TRUE(path.has_value()) << "irgs-robot printed no pty path";
  ASSERT_EQ(path->rfind("/dev/pts/", 0), 0u) << *path;
  Port port(*path);
  ASSERT_TRUE(port.ok()) << "cannot open " << *path;

  std::vector<OdometrySample> odometry;
  std::vector<double> sonar_times;  // robot time of each DISTANCE_SENSOR
  bool saw_heartbeat = false;
  auto collect = [&](const std::vector<mav::Frame>& frames) {
    for (const auto& f : frames) {
      if (auto o = f.as<mav::Odometry>())
        odometry.push_back({static_cast<double>(o->time_usec) * 1e-6, o->x, o->y, o->vx});
      else if (auto d = f.as<mav::DistanceSensor>())
        sonar_times.push_back(d->time_boot_ms * 1e-3);
      else if (auto h = f.as<mav::Heartbeat>())
        saw_heartbeat =
            saw_heartbeat || h->type == static_cast<std::uint8_t>(mav::MavType::kGroundRover);
    }
  };

  // Drive: heartbeats at 2 Hz, MANUAL_CONTROL at 10 Hz, for 1.5 s.
  mav::Heartbeat hb;
  hb.type = static_cast<std::uint8_t>(mav::MavType::kGcs);
  mav::ManualControl mc;
  mc.target = 1;
  mc.x = 600;
  const auto t0 = Clock::now();
  double next_hb = 0.0;
  double next_mc = 0.0;
  double last_robot_time_before_final_mc = 0.0;
  while (since(t0) < 1.5) {
    if (since(t0) >= next_hb) {
      port.send(hb);
      next_hb += 0.5;
    }
    if (since(t0) >= next_mc) {
      if (!odometry.empty())
        last_robot_time_before_final_mc = odometry.back().robot_s;
      port.send(mc);
      next_mc += 0.1;
    }
    collect(port.receive(0.02));
  }
  ASSERT_TRUE(saw_heartbeat);
  ASSERT_GE(odometry.size(), 10u);
  const std::size_t driving_end = odometry.size();
  const double moved =
      std::hypot(odometry.back().x - odometry.front().x, odometry.back().y - odometry.front().y);
  EXPECT_GT(moved, 0.1) << "no forward motion in ODOMETRY";
  EXPECT_GT(odometry.back().vx, 0.1);

  // Rates, on the robot's timestamps over what arrived.
  const double odo_span = odometry.back().robot_s - odometry.front().robot_s;
  EXPECT_GE((static_cast<double>(odometry.size()) - 1.0) / odo_span, 19.0);
  ASSERT_GE(sonar_times.size(), 10u);
  const double sonar_span = sonar_times.back() - sonar_times.front();
  EXPECT_GE((static_cast<double>(sonar_times.size()) - 1.0) / sonar_span, 20.0);

  // Stop sending MANUAL_CONTROL (heartbeats continue): the robot must stop within 0.5 s.
  const auto stop_t0 = Clock::now();
  while (since(stop_t0) < 1.2) {
    if (since(t0) >= next_hb) {
      port.send(hb);
      next_hb += 0.5;
    }
    collect(port.receive(0.02));
  }
  std::optional<double> stop_robot_s;
  for (std::size_t i = driving_end; i < odometry.size(); ++i) {
    if (odometry[i].vx == 0.0 && !stop_robot_s)
      stop_robot_s = odometry[i].robot_s;
    if (stop_robot_s) {
      EXPECT_EQ(odometry[i].vx, 0.0) << "moving again at " << odometry[i].robot_s;
    }
  }
  ASSERT_TRUE(stop_robot_s.has_value()) << "never stopped";
  // The last ODOMETRY seen before the final MANUAL_CONTROL was sent precedes that send, so
  // this bound is conservative.
  EXPECT_LE(*stop_robot_s - last_robot_time_before_final_mc, 0.5 + 0.05);
  EXPECT_EQ(port.totals().bad_crc, 0u);

  EXPECT_EQ(robot.terminate(SIGTERM, 5.0), 0) << "no clean exit on SIGTERM";
}

// The services of docs/protocol.md sections 12-14 on the real executable: a parameter set and
// read back, SYS_STATUS and SCALED_IMU streaming, and a one-waypoint mission 0.25 m ahead
// uploaded, started and reported reached.
TEST(IrgsRobotEndToEnd, SetsAParameterAndRunsAnUploadedMissionOverThePty) {
  Child robot({IRGS_ROBOT_EXE, "--ideal", "--seed", "4"});
  ASSERT_TRUE(robot.started());
  const auto path = robot.readLine(20.0);
  ASSERT_TRUE(path.has_value()) << "irgs-robot printed no pty path";
  Port port(*path);
  ASSERT_TRUE(port.ok()) << "cannot open " << *path;

  mav::Heartbeat hb;
  hb.type = static_cast<std::uint8_t>(mav::MavType::kGcs);
  std::optional<mav::Odometry> pose;
  std::optional<float> sr_pose;
  std::optional<std::uint8_t> mission_ack;
  std::optional<std::uint8_t> start_ack;
  bool reached = false;
  bool sys_status = false;
  bool imu = false;
  auto handle = [&](const std::vector<mav::Frame>& frames) {
    for (const auto& f : frames) {
      if (auto o = f.as<mav::Odometry>()) {
        pose = *o;
      } else if (auto v = f.as<mav::ParamValue>()) {
        if (std::string(v->param_id.data(), strnlen(v->param_id.data(), 16)) == "SR_POSE")
          sr_pose = v->param_value;
      } else if (auto r = f.as<mav::MissionRequestInt>()) {
        ASSERT_TRUE(pose.has_value());
        // 0.25 m straight ahead of the odometry pose (NED x/y, yaw from the quaternion).
        const double yaw = 2.0 * std::atan2(pose->q[3], pose->q[0]);
        mav::MissionItemInt item;
        item.target_system = 1;
        item.seq = r->seq;
        item.frame = static_cast<std::uint8_t>(mav::MavFrame::kLocalNed);
        item.command = static_cast<std::uint16_t>(mav::MavCmd::kNavWaypoint);
        item.x = static_cast<std::int32_t>(std::lround((pose->x + 0.25 * std::cos(yaw)) * 1e4));
        item.y = static_cast<std::int32_t>(std::lround((pose->y + 0.25 * std::sin(yaw)) * 1e4));
        port.send(item);
      } else if (auto a = f.as<mav::MissionAck>()) {
        mission_ack = a->type;
      } else if (auto c = f.as<mav::CommandAck>()) {
        if (c->command == static_cast<std::uint16_t>(mav::MavCmd::kMissionStart))
          start_ack = c->result;
      } else if (auto m = f.as<mav::MissionItemReached>()) {
        reached = reached || m->seq == 0;
      } else if (f.as<mav::SysStatus>()) {
        sys_status = true;
      } else if (f.as<mav::ScaledImu>()) {
        imu = true;
      }
    }
  };
  const auto t0 = Clock::now();
  double next_hb = 0.0;
  enum class Step { kWaitPose, kParam, kUpload, kStart, kRun, kDone } step = Step::kWaitPose;
  while (since(t0) < 20.0 && step != Step::kDone) {
    if (since(t0) >= next_hb) {
      port.send(hb);
      next_hb += 0.5;
    }
    handle(port.receive(0.02));
    if (step == Step::kWaitPose && pose) {
      mav::ParamSet set;
      set.target_system = 1;
      const std::string id = "SR_POSE";
      std::copy(id.begin(), id.end(), set.param_id.begin());
      set.param_value = 10.0f;
      set.param_type = static_cast<std::uint8_t>(mav::MavParamType::kReal32);
      port.send(set);
      step = Step::kParam;
    } else if (step == Step::kParam && sr_pose) {
      mav::MissionCount count;
      count.target_system = 1;
      count.count = 1;
      port.send(count);
      step = Step::kUpload;
    } else if (step == Step::kUpload && mission_ack) {
      ASSERT_EQ(*mission_ack, static_cast<std::uint8_t>(mav::MavMissionResult::kAccepted));
      mav::CommandLong start;
      start.target_system = 1;
      start.command = static_cast<std::uint16_t>(mav::MavCmd::kMissionStart);
      port.send(start);
      step = Step::kStart;
    } else if (step == Step::kStart && start_ack) {
      ASSERT_EQ(*start_ack, static_cast<std::uint8_t>(mav::MavResult::kAccepted));
      step = Step::kRun;
    } else if (step == Step::kRun && reached) {
      step = Step::kDone;
    }
  }
  EXPECT_EQ(step, Step::kDone) << "stuck at step " << static_cast<int>(step);
  ASSERT_TRUE(sr_pose.has_value());
  EXPECT_FLOAT_EQ(*sr_pose, 10.0f);
  EXPECT_TRUE(reached);
  EXPECT_TRUE(sys_status);
  EXPECT_TRUE(imu);
  EXPECT_EQ(port.totals().bad_crc, 0u);
  EXPECT_EQ(robot.terminate(SIGTERM, 5.0), 0);
}

TEST(IrgsRobotEndToEnd, ServesAsATcpServerAndExitsCleanlyOnSigint) {
  Child robot({IRGS_ROBOT_EXE, "--tcp", "0"});
  ASSERT_TRUE(robot.started());
  const auto line = robot.readLine(20.0);
  ASSERT_TRUE(line.has_value());
  ASSERT_EQ(line->rfind("tcp ", 0), 0u) << *line;
  const int port = std::stoi(line->substr(4));
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  ASSERT_GE(fd, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(static_cast<std::uint16_t>(port));
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ASSERT_EQ(::connect(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr), 0);
  mav::FrameDecoder decoder;
  std::vector<mav::Frame> frames;
  bool heartbeat = false;
  const auto t0 = Clock::now();
  while (!heartbeat && since(t0) < 5.0) {
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, 100) <= 0)
      continue;
    std::uint8_t buf[4096];
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n <= 0)
      break;
    frames.clear();
    decoder.feed(std::span<const std::uint8_t>(buf, static_cast<std::size_t>(n)), frames);
    for (const auto& f : frames)
      heartbeat = heartbeat || f.as<mav::Heartbeat>().has_value();
  }
  ::close(fd);
  EXPECT_TRUE(heartbeat);
  EXPECT_EQ(robot.terminate(SIGINT, 5.0), 0);
}

TEST(IrgsRobotEndToEnd, LinkOptionCreatesASymlinkToThePtyAndRemovesItOnExit) {
  namespace fs = std::filesystem;
  const fs::path link =
      fs::temp_directory_path() / ("irgs_robot_e2e_link_" + std::to_string(::getpid()));
  fs::remove(link);
  Child robot({IRGS_ROBOT_EXE, "--pty", "--link", link.string()});
  ASSERT_TRUE(robot.started());
  const auto path = robot.readLine(20.0);
  ASSERT_TRUE(path.has_value());
  ASSERT_TRUE(fs::is_symlink(link));
  EXPECT_EQ(fs::read_symlink(link).string(), *path);
  EXPECT_EQ(robot.terminate(SIGTERM, 5.0), 0);
  EXPECT_FALSE(fs::is_symlink(link));
  fs::remove(link);
}

TEST(IrgsRobotEndToEnd, BadArgumentsAreUsageErrors) {
  Child robot({IRGS_ROBOT_EXE, "--baud", "fast"});
  ASSERT_TRUE(robot.started());
  EXPECT_EQ(robot.terminate(0, 10.0), 2);
}

}  // namespace
