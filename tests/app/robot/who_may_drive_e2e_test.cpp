// End to end, "who may drive" (issue 24, item 6; docs/protocol.md): the irgs-robot executable as
// a TCP server on loopback, ground stations in this test process (raw sockets, our own
// FrameEncoder/FrameDecoder) and irgs-sim --connect. What moves the robot is read from its
// --log-motion lines and the ODOMETRY it streams. Every wait has a deadline; children are always
// reaped.

#include <arpa/inet.h>
#include <fcntl.h>
#include <ifaddrs.h>
#include <net/if.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <signal.h>
#include <sys/socket.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "comms/mavlink/frame_decoder.hpp"
#include "comms/mavlink/frame_encoder.hpp"
#include "comms/mavlink/messages.hpp"
#include "comms/mavlink/signing_key.hpp"
#include "tests/app/sim/child_process.hpp"

namespace {

namespace fs = std::filesystem;
namespace mav = irgs::comms::mavlink;
using irgs::test::Child;
using irgs::test::Clock;
using irgs::test::since;

// A ground station on a TCP connection (or a connected UDP socket) to irgs-robot: sends what it
// is told, reads and decodes what arrives (verifying signatures when it has a key), notices when
// the robot closes a TCP connection.
class TcpStation {
 public:
  TcpStation(std::uint16_t port, std::uint8_t system_id, std::optional<mav::SigningKey> key = {},
             bool udp = false, std::uint32_t address = INADDR_LOOPBACK)
      : encoder_(system_id, 190), key_(key), udp_(udp) {
    if (key_) {
      encoder_.enableSigning(*key_, 0);
      decoder_.setSigningKey(key_, /*require_signed=*/true);
    }
    fd_ = ::socket(AF_INET, udp ? SOCK_DGRAM : SOCK_STREAM, 0);
    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_port = htons(port);
    addr.sin_addr.s_addr = htonl(address);
    connected_ = fd_ >= 0 && ::connect(fd_, reinterpret_cast<sockaddr*>(&addr), sizeof addr) == 0;
    if (connected_) {
      const int one = 1;
      if (!udp)
        ::setsockopt(fd_, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
      ::fcntl(fd_, F_SETFL, ::fcntl(fd_, F_GETFL) | O_NONBLOCK);
      sockaddr_in local{};
      socklen_t len = sizeof local;
      ::getsockname(fd_, reinterpret_cast<sockaddr*>(&local), &len);
      local_port_ = ntohs(local.sin_port);
    }
  }
  ~TcpStation() { disconnect(); }
  TcpStation(const TcpStation&) = delete;
  TcpStation& operator=(const TcpStation&) = delete;

  bool connected() const { return connected_; }
  bool closedByRobot() const { return closed_; }
  std::uint16_t localPort() const { return local_port_; }
  void disconnect() {
    if (fd_ >= 0)
      ::close(fd_);
    fd_ = -1;
  }

  template <class M>
  void send(const M& message) {
    const mav::EncodedFrame frame =
        encoder_.encode(message, mav::signingTimestampAt(std::chrono::system_clock::now()));
    sendBytes(std::vector<std::uint8_t>(frame.view().begin(), frame.view().end()));
  }
  void sendBytes(const std::vector<std::uint8_t>& bytes) {
    if (fd_ < 0 || closed_)
      return;
    if (::send(fd_, bytes.data(), bytes.size(), MSG_NOSIGNAL) == static_cast<ssize_t>(bytes.size()))
      sent_.insert(sent_.end(), bytes.begin(), bytes.end());
  }
  void heartbeat() {
    mav::Heartbeat hb;
    hb.type = static_cast<std::uint8_t>(mav::MavType::kGcs);
    send(hb);
  }
  void manual(std::int16_t x, std::int16_t r) {
    mav::ManualControl mc;
    mc.target = 1;
    mc.x = x;
    mc.r = r;
    send(mc);
  }

  // Reads for up to `timeout_s` (returns earlier once something arrived).
  void pump(double timeout_s) {
    if (fd_ < 0 || closed_)
      return;
    pollfd p{fd_, POLLIN, 0};
    if (::poll(&p, 1, static_cast<int>(timeout_s * 1000)) <= 0)
      return;
    std::uint8_t buf[8192];
    for (;;) {
      const ssize_t n = ::recv(fd_, buf, sizeof buf, 0);
      if (n > 0) {
        decoder_.feed(std::span<const std::uint8_t>(buf, static_cast<std::size_t>(n)), frames_);
        continue;
      }
      // UDP has no connection to close (an ICMP error is not the robot closing anything).
      if (!udp_ && (n == 0 || (errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR)))
        closed_ = true;
      if (udp_ && n < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR)
        continue;
      return;
    }
  }

  std::vector<std::string> statusTexts() const {
    std::vector<std::string> out;
    for (const mav::Frame& f : frames_)
      if (auto s = f.as<mav::Statustext>())
        out.emplace_back(s->text.data(), strnlen(s->text.data(), s->text.size()));
    return out;
  }
  bool said(const std::string& needle) const {
    for (const std::string& text : statusTexts())
      if (text.find(needle) != std::string::npos)
        return true;
    return false;
  }
  std::vector<mav::Odometry> odometry(std::size_t from = 0) const {
    std::vector<mav::Odometry> out;
    for (std::size_t i = from; i < frames_.size(); ++i)
      if (auto o = frames_[i].as<mav::Odometry>())
        out.push_back(*o);
    return out;
  }
  std::optional<mav::SysStatus> lastSysStatus() const {
    std::optional<mav::SysStatus> last;
    for (const mav::Frame& f : frames_)
      if (auto s = f.as<mav::SysStatus>())
        last = *s;
    return last;
  }
  std::size_t frameCount() const { return frames_.size(); }
  const std::vector<mav::Frame>& frames() const { return frames_; }
  const mav::DecodeCounters& readerTotals() const { return decoder_.totals(); }
  const std::vector<std::uint8_t>& sent() const { return sent_; }

 private:
  mav::FrameEncoder encoder_;
  mav::FrameDecoder decoder_;
  std::optional<mav::SigningKey> key_;
  bool udp_ = false;
  int fd_ = -1;
  bool connected_ = false;
  bool closed_ = false;
  std::uint16_t local_port_ = 0;
  std::vector<mav::Frame> frames_;
  std::vector<std::uint8_t> sent_;
};

// Drives `stations` for `seconds`: each one gets a heartbeat every 0.3 s and, when it has a
// command, MANUAL_CONTROL every 0.1 s; everything they receive is read meanwhile.
struct Drive {
  TcpStation* station;
  std::optional<std::pair<std::int16_t, std::int16_t>> command;  // x, r
};
void drive(std::vector<Drive> drives, double seconds) {
  const auto t0 = Clock::now();
  double next_hb = 0.0;
  double next_mc = 0.0;
  while (since(t0) < seconds) {
    const double t = since(t0);
    const bool hb = t >= next_hb;
    const bool mc = t >= next_mc;
    for (Drive& d : drives) {
      if (hb)
        d.station->heartbeat();
      if (mc && d.command)
        d.station->manual(d.command->first, d.command->second);
    }
    if (hb)
      next_hb += 0.3;
    if (mc)
      next_mc += 0.1;
    for (Drive& d : drives)
      d.station->pump(0.01);
  }
}

// Heading change (rad, yaw of the ODOMETRY quaternion) between two samples.
double yawOf(const mav::Odometry& o) {
  return std::atan2(2.0 * (o.q[0] * o.q[3] + o.q[1] * o.q[2]),
                    1.0 - 2.0 * (o.q[2] * o.q[2] + o.q[3] * o.q[3]));
}

std::uint16_t announcedPort(Child& robot, const std::string& kind = "tcp") {
  if (!robot.waitOutput(kind + " ", 20.0))
    return 0;
  const std::string& out = robot.output();
  const auto at = out.find(kind + " ");
  return static_cast<std::uint16_t>(std::stoi(out.substr(at + kind.size() + 1)));
}

// An IPv4 address of this computer other than loopback (host order), if it has one.
std::optional<std::uint32_t> nonLoopbackAddress() {
  ifaddrs* list = nullptr;
  if (::getifaddrs(&list) != 0)
    return std::nullopt;
  std::optional<std::uint32_t> found;
  for (const ifaddrs* i = list; i != nullptr && !found; i = i->ifa_next) {
    if (i->ifa_addr == nullptr || i->ifa_addr->sa_family != AF_INET || (i->ifa_flags & IFF_UP) == 0)
      continue;
    const auto address = ntohl(reinterpret_cast<const sockaddr_in*>(i->ifa_addr)->sin_addr.s_addr);
    if ((address >> 24) != 127)
      found = address;
  }
  ::freeifaddrs(list);
  return found;
}

std::size_t count(const std::string& text, const std::string& needle) {
  std::size_t n = 0;
  for (auto at = text.find(needle); at != std::string::npos; at = text.find(needle, at + 1))
    ++n;
  return n;
}

class WhoMayDrive : public ::testing::Test {
 protected:
  void SetUp() override {
    work_ = fs::temp_directory_path() /
            ("irgs_who_may_drive_" + std::to_string(::getpid()) + "_" +
             ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(work_);
    fs::create_directories(work_);
  }
  void TearDown() override { fs::remove_all(work_); }

  // A fixed key (a test's key, not a secret) in a key file, as the GUI exports it.
  fs::path writeKey() {
    const fs::path file = work_ / "robot.key";
    EXPECT_EQ(mav::saveSigningKeyFile(file, key()), "");
    return file;
  }
  static mav::SigningKey key() {
    mav::SigningKey k{};
    for (std::size_t i = 0; i < k.size(); ++i)
      k[i] = static_cast<std::uint8_t>(0xa5 ^ (31 * i));
    return k;
  }

  fs::path work_;
};

TEST_F(WhoMayDrive, ASecondTcpClientCannotDriveARobotAnotherClientIsDriving) {
  Child robot({IRGS_ROBOT_EXE, "--tcp", "0", "--ideal", "--seed", "3", "--log-motion",
               "--gcs-timeout", "1.0"});
  ASSERT_TRUE(robot.started());
  const std::uint16_t port = announcedPort(robot);
  ASSERT_NE(port, 0) << robot.output();

  // Client 1 drives straight ahead.
  TcpStation first(port, 255);
  ASSERT_TRUE(first.connected());
  drive({{&first, std::make_pair<std::int16_t, std::int16_t>(500, 0)}}, 1.0);
  ASSERT_TRUE(robot.waitOutput("motion start", 5.0)) << robot.output();
  ASSERT_FALSE(first.odometry().empty());
  const std::size_t second_arrives = first.frameCount();

  // Client 2 connects and commands reverse and a hard spin while client 1 keeps driving.
  TcpStation second(port, 250);
  ASSERT_TRUE(second.connected());
  drive({{&first, std::make_pair<std::int16_t, std::int16_t>(500, 0)},
         {&second, std::make_pair<std::int16_t, std::int16_t>(-800, 1000)}},
        1.5);
  EXPECT_TRUE(second.closedByRobot()) << "the robot kept the second client";
  EXPECT_TRUE(second.said("busy: another ground station is driving"));
  const std::string refused = "refused client 127.0.0.1:" + std::to_string(second.localPort());
  EXPECT_TRUE(first.said(refused)) << "client 1 was not told";
  EXPECT_FALSE(first.closedByRobot());
  robot.pump(0.1);
  EXPECT_NE(robot.output().find("irgs-robot: " + refused), std::string::npos) << robot.output();

  // The motion followed client 1 only: forward, never reversing, no turn.
  const auto during = first.odometry(second_arrives);
  ASSERT_GE(during.size(), 20u);
  double min_vx = 1e9;
  for (const auto& o : during)
    min_vx = std::min(min_vx, static_cast<double>(o.vx));
  EXPECT_GT(min_vx, 0.1) << "the robot slowed or reversed";
  EXPECT_LT(std::abs(yawOf(during.back()) - yawOf(during.front())), 0.02) << "the robot turned";
  EXPECT_EQ(count(robot.output(), "motion start"), 1u) << robot.output();

  // Client 1 goes silent (connected, sending nothing): after the ground-station timeout it no
  // longer blocks a newcomer, which is let in and drives.
  first.pump(0.0);
  ASSERT_TRUE(robot.waitOutput("motion stop", 3.0)) << robot.output();
  const auto silent_since = Clock::now();
  while (since(silent_since) < 1.3)
    first.pump(0.05);  // read, send nothing
  TcpStation third(port, 250);
  ASSERT_TRUE(third.connected());
  drive({{&third, std::make_pair<std::int16_t, std::int16_t>(0, 800)}}, 1.0);
  EXPECT_FALSE(third.closedByRobot());
  const auto turning = third.odometry();
  ASSERT_GE(turning.size(), 10u) << "the newcomer gets no telemetry";
  EXPECT_GT(std::abs(yawOf(turning.back()) - yawOf(turning.front())), 0.1) << "it did not turn";
  first.pump(0.2);
  EXPECT_TRUE(first.closedByRobot()) << "the silent client was not replaced";

  robot.signal(SIGTERM);
  EXPECT_EQ(robot.wait(10.0), 0) << robot.output();
}

TEST_F(WhoMayDrive,
       WithASigningKeyUnsignedManualControlFromAnotherProcessMovesNothingAndIsCounted) {
  const fs::path key_file = writeKey();
  Child robot({IRGS_ROBOT_EXE, "--tcp", "0", "--ideal", "--seed", "3", "--log-motion",
               "--signing-key", key_file.string()});
  ASSERT_TRUE(robot.started());
  const std::uint16_t port = announcedPort(robot);
  ASSERT_NE(port, 0) << robot.output();
  EXPECT_NE(robot.output().find("key fingerprint " + mav::signingKeyFingerprint(key())),
            std::string::npos)
      << robot.output();

  // Another process without the key: heartbeats and MANUAL_CONTROL for 2.2 s (two SYS_STATUS).
  {
    TcpStation unsigned_station(port, 255);
    ASSERT_TRUE(unsigned_station.connected());
    drive({{&unsigned_station, std::make_pair<std::int16_t, std::int16_t>(600, 0)}}, 2.2);
    EXPECT_FALSE(unsigned_station.closedByRobot());
    const auto odometry = unsigned_station.odometry();
    ASSERT_GE(odometry.size(), 20u);  // telemetry flows (signed: shown unverified)
    for (const auto& o : odometry)
      EXPECT_EQ(o.vx, 0.0f);
    EXPECT_TRUE(unsigned_station.said("unsigned/bad signature: "));
    const auto status = unsigned_station.lastSysStatus();
    ASSERT_TRUE(status);
    EXPECT_GE(status->errors_comm, 10u);
    EXPECT_EQ(status->drop_rate_comm, 10000u);
  }
  robot.pump(0.1);
  EXPECT_EQ(robot.output().find("motion start"), std::string::npos) << robot.output();
  EXPECT_NE(robot.output().find("irgs-robot: signing: "), std::string::npos) << robot.output();

  // A ground station with the key drives (its predecessor left: the robot is free).
  std::vector<std::uint8_t> recorded;
  {
    TcpStation signed_station(port, 255, key());
    ASSERT_TRUE(signed_station.connected());
    drive({{&signed_station, std::make_pair<std::int16_t, std::int16_t>(600, 0)}}, 1.0);
    ASSERT_TRUE(robot.waitOutput("motion start", 5.0)) << robot.output();
    const auto odometry = signed_station.odometry();
    ASSERT_FALSE(odometry.empty());
    EXPECT_GT(odometry.back().vx, 0.1);
    EXPECT_EQ(signed_station.readerTotals().bad_signature, 0u);  // the robot signs with the key
    recorded = signed_station.sent();
  }
  ASSERT_TRUE(robot.waitOutput("motion stop", 5.0)) << robot.output();

  // Replaying what the signed station sent, from another connection, three times over 1.8 s:
  // nothing moves, and the robot's error count (SYS_STATUS, 1 Hz) grows meanwhile.
  {
    TcpStation replayer(port, 254);
    ASSERT_TRUE(replayer.connected());
    const auto t0 = Clock::now();
    for (int round = 0; round < 3; ++round) {
      replayer.sendBytes(recorded);
      while (since(t0) < 0.6 * (round + 1))
        replayer.pump(0.05);
    }
    std::vector<std::uint16_t> errors;
    for (const mav::Frame& f : replayer.frames())
      if (auto st = f.as<mav::SysStatus>())
        errors.push_back(st->errors_comm);
    ASSERT_GE(errors.size(), 2u);
    EXPECT_GT(errors.back(), errors.front()) << "replayed frames were not counted";
  }
  robot.pump(0.1);
  EXPECT_EQ(count(robot.output(), "motion start"), 1u) << robot.output();

  robot.signal(SIGTERM);
  EXPECT_EQ(robot.wait(10.0), 0) << robot.output();
}

TEST_F(WhoMayDrive, ASecondUdpSenderCannotDriveWhileTheFirstIsAlive) {
  Child robot({IRGS_ROBOT_EXE, "--udp", "0", "--ideal", "--seed", "3", "--log-motion"});
  ASSERT_TRUE(robot.started());
  const std::uint16_t port = announcedPort(robot, "udp");
  ASSERT_NE(port, 0) << robot.output();
  TcpStation first(port, 255, std::nullopt, /*udp=*/true);
  TcpStation second(port, 250, std::nullopt, /*udp=*/true);
  ASSERT_TRUE(first.connected() && second.connected());
  drive({{&first, std::make_pair<std::int16_t, std::int16_t>(500, 0)}}, 0.8);
  ASSERT_TRUE(robot.waitOutput("motion start", 5.0)) << robot.output();
  const std::size_t second_arrives = first.frameCount();
  drive({{&first, std::make_pair<std::int16_t, std::int16_t>(500, 0)},
         {&second, std::make_pair<std::int16_t, std::int16_t>(-800, 1000)}},
        1.2);
  EXPECT_EQ(second.frameCount(), 0u) << "the robot answered the second sender";
  EXPECT_TRUE(first.said("refused client 127.0.0.1:" + std::to_string(second.localPort())));
  const auto during = first.odometry(second_arrives);
  ASSERT_GE(during.size(), 15u);
  for (const auto& o : during)
    EXPECT_GT(o.vx, 0.1f);
  EXPECT_LT(std::abs(yawOf(during.back()) - yawOf(during.front())), 0.02) << "the robot turned";
  robot.signal(SIGTERM);
  EXPECT_EQ(robot.wait(10.0), 0) << robot.output();
}

// Issue 24: "listening transports bind to loopback unless an address is given". Needs a
// non-loopback IPv4 address on this computer to knock on.
TEST_F(WhoMayDrive, TheTcpServerIsOnLoopbackUnlessGivenAnAddress) {
  const std::optional<std::uint32_t> lan = nonLoopbackAddress();
  if (!lan)
    GTEST_SKIP() << "no non-loopback IPv4 address on this computer";
  Child local({IRGS_ROBOT_EXE, "--tcp", "0"});
  const std::uint16_t local_port = announcedPort(local);
  ASSERT_NE(local_port, 0) << local.output();
  EXPECT_TRUE(TcpStation(local_port, 255).connected());
  EXPECT_FALSE(TcpStation(local_port, 255, std::nullopt, false, *lan).connected())
      << "reachable from the network without being asked to";
  Child everywhere({IRGS_ROBOT_EXE, "--tcp", "0.0.0.0:0"});
  const std::uint16_t port = announcedPort(everywhere);
  ASSERT_NE(port, 0) << everywhere.output();
  EXPECT_TRUE(TcpStation(port, 255, std::nullopt, false, *lan).connected());
}

// Issue 24, link case (d): `--baud` below 38400 selects the compact telemetry also over TCP,
// where it names the serial link behind a bridge (before, a 9600-baud relay was flooded with the
// full profile at ~10.8 kB/s and the heartbeat drowned: link lost, reconnect, forever).
TEST_F(WhoMayDrive, ASlowBaudOverTcpSendsTheCompactTelemetryWithinItsBudget) {
  Child robot({IRGS_ROBOT_EXE, "--tcp", "0", "--baud", "9600", "--ideal"});
  const std::uint16_t port = announcedPort(robot);
  ASSERT_NE(port, 0) << robot.output();
  TcpStation station(port, 255);
  ASSERT_TRUE(station.connected());
  const auto t0 = Clock::now();
  while (std::chrono::duration<double>(Clock::now() - t0).count() < 4.0) {
    station.heartbeat();
    station.pump(0.25);
  }
  std::size_t compact = 0, full = 0, bytes = 0;
  for (const mav::Frame& f : station.frames()) {
    compact += f.as<mav::IrgsPose2d>() ? 1 : 0;
    full += f.as<mav::Odometry>() || f.as<mav::LocalPositionNed>() ? 1 : 0;
    bytes += f.payload_length + 12u;  // MAVLink 2 header and checksum, unsigned
  }
  EXPECT_GT(compact, 20u);  // IRGS_POSE_2D at 10 Hz
  EXPECT_EQ(full, 0u);
  EXPECT_LT(static_cast<double>(bytes) / 4.0, 960.0) << bytes << " bytes in 4 s";
  robot.signal(SIGTERM);
  EXPECT_EQ(robot.wait(10.0), 0) << robot.output();
}

TEST_F(WhoMayDrive, BadListenAndKeyArgumentsAreClearErrors) {
  const auto run = [](std::vector<std::string> args) {
    args.insert(args.begin(), IRGS_ROBOT_EXE);
    auto child = std::make_unique<Child>(args);
    const int status = child->wait(20.0);
    return std::make_pair(status, child->output());
  };
  auto [status, out] = run({"--tcp", "localhost:"});
  EXPECT_EQ(status, 2) << out;
  EXPECT_NE(out.find("--tcp needs PORT or ADDR:PORT"), std::string::npos) << out;
  std::tie(status, out) = run({"--tcp", "0", "--udp", "0"});
  EXPECT_EQ(status, 2) << out;
  std::tie(status, out) = run({"--tcp", "0", "--signing-key", (work_ / "missing.key").string()});
  EXPECT_EQ(status, 1) << out;
  EXPECT_NE(out.find("cannot read signing key file"), std::string::npos) << out;
  std::tie(status, out) =
      run({"--protocol", "arcos", "--tcp", "0", "--signing-key", writeKey().string()});
  EXPECT_EQ(status, 2) << out;
  EXPECT_NE(out.find("ARCOS has no signing"), std::string::npos) << out;
}

// Headless users and scripts: irgs-sim --connect takes the key file too.
TEST_F(WhoMayDrive, IrgsSimDrivesASignedRobotOnlyWithTheKey) {
  const fs::path key_file = writeKey();
  Child robot({IRGS_ROBOT_EXE, "--tcp", "0", "--seed", "4", "--log-motion", "--signing-key",
               key_file.string()});
  ASSERT_TRUE(robot.started());
  const std::uint16_t port = announcedPort(robot);
  ASSERT_NE(port, 0) << robot.output();
  const std::string url = "tcp://127.0.0.1:" + std::to_string(port);
  const fs::path script = work_ / "drive.txt";
  std::ofstream(script) << "0 drive 0.25 0\n1.5 stop\n";

  Child without({IRGS_SIM_EXE, "--connect", url, "--script", script.string(), "--out",
                 (work_ / "unsigned").string(), "--connect-timeout", "10"});
  ASSERT_TRUE(without.started());
  without.wait(60.0);
  robot.pump(0.1);
  EXPECT_EQ(robot.output().find("motion start"), std::string::npos) << robot.output();

  Child with({IRGS_SIM_EXE, "--connect", url, "--signing-key", key_file.string(), "--script",
              script.string(), "--out", (work_ / "signed").string(), "--connect-timeout", "10"});
  ASSERT_TRUE(with.started());
  ASSERT_EQ(with.wait(60.0), 0) << with.output();
  robot.pump(0.1);
  EXPECT_NE(robot.output().find("motion start"), std::string::npos) << robot.output();

  robot.signal(SIGTERM);
  EXPECT_EQ(robot.wait(10.0), 0) << robot.output();
}

}  // namespace
