// irgs-robot: the virtual robot firmware. Runs the core simulator in real time and serves it over
// MAVLink 2 on a pseudo-terminal (default; prints the /dev/pts/N path on stdout) or as a TCP
// server. All I/O and the stepping timer run on the one comms IoThread; the main thread waits
// for SIGINT/SIGTERM.

#include <fcntl.h>
#include <signal.h>
#include <stdlib.h>
#include <termios.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <future>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <boost/asio/post.hpp>
#include <boost/asio/steady_timer.hpp>

#include "app/robot/arcos_firmware.hpp"
#include "app/robot/arrival_rate_meter.hpp"
#include "app/robot/firmware_core.hpp"
#include "comms/mavlink/frame_decoder.hpp"
#include "comms/mavlink/messages.hpp"
#include "comms/transport/io_thread.hpp"
#include "comms/transport/tcp_transport.hpp"
#include "core/robot/robot_profile_file.hpp"
#include "core/sim/sim_presets.hpp"
#include "core/world/map_file.hpp"

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

constexpr int kExitFiles = 1;
constexpr int kExitUsage = 2;
constexpr int kExitIo = 3;

const char* const kUsage =
    "usage: irgs-robot [--map FILE] [--robot FILE] [--seed N] [--pty [--link PATH]]\n"
    "                  [--tcp PORT] [--baud N] [--rate HZ] [--gcs-timeout S] [--ideal]\n"
    "                  [--log-motion] [--protocol mavlink|arcos] [--watchdog S] [--strict]\n"
    "  Serves the simulated robot over MAVLink 2. Without --tcp it opens a pseudo-terminal,\n"
    "  prints its path (/dev/pts/N) on stdout and serves on it; --link PATH also creates a\n"
    "  symlink PATH to it. --tcp PORT serves as a TCP server (0 = any free port; the port is\n"
    "  printed as 'tcp PORT'). --baud N limits the pty output to N/10 bytes/s like a UART\n"
    "  (default 115200); below 38400 the compact profile is sent (IRGS_POSE_2D 10 Hz,\n"
    "  IRGS_SONAR_SCAN 5 Hz). --rate HZ: odometry and sonar telemetry rate (default 20).\n"
    "  --gcs-timeout S: stop when ground-station heartbeats are missing S seconds (1.5).\n"
    "  --ideal: no odometry or sensor errors. Defaults: bundled default map and thesis robot.\n"
    "  --log-motion: print 'motion start|stop t=S mono=S' on stdout when the robot starts or\n"
    "  stops moving (t: firmware time, mono: CLOCK_MONOTONIC seconds, for end-to-end tests).\n"
    "  --protocol arcos: serve as a Pioneer over ARCOS/P2OS instead (docs/pioneer.md); use a\n"
    "  Pioneer profile (--robot resources/robots/pioneer_p3dx.json) and --tcp 8101 like\n"
    "  MobileSim. --watchdog S: ARCOS PULSE watchdog (default: the profile's, 2 s).\n"
    "  --strict (ARCOS): behave as the Pioneer manuals say a real robot does: commands closer\n"
    "  than 5 ms to the previous one are lost, malformed packets ignored, the watchdog resumes\n"
    "  the old set points on the next command (docs/pioneer.md).\n"
    "  On exit it prints what arrived on the wire: ARCOS command packets or MANUAL_CONTROLs,\n"
    "  total, mean and peak per second (and, for ARCOS, what was dropped and why).\n";

struct Options {
  fs::path map = fs::path(IRGS_RESOURCE_DIR) / "maps/default.json";
  fs::path robot = fs::path(IRGS_RESOURCE_DIR) / "robots/thesis_robot.json";
  std::uint64_t seed = 1;
  std::optional<std::uint16_t> tcp_port;
  std::string link;
  std::uint32_t baud = 115200;
  double rate_hz = 20.0;
  double gcs_timeout_s = 1.5;
  bool ideal = false;
  bool log_motion = false;
  bool arcos = false;                // --protocol arcos
  bool strict = false;               // --strict (ARCOS)
  std::optional<double> watchdog_s;  // --watchdog (ARCOS)
};

bool parseNumber(const std::string& text, double& out) {
  try {
    std::size_t used = 0;
    out = std::stod(text, &used);
    return used == text.size() && std::isfinite(out);
  } catch (const std::exception&) {
    return false;
  }
}

// Returns an error message, empty on success; sets help when --help was given.
std::string parseOptions(int argc, char** argv, Options& o, bool& help) {
  bool pty = false;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&](std::string& out) {
      if (i + 1 >= argc)
        return false;
      out = argv[++i];
      return true;
    };
    std::string v;
    double number = 0.0;
    if (arg == "--help" || arg == "-h") {
      help = true;
      return {};
    } else if (arg == "--pty") {
      pty = true;
    } else if (arg == "--ideal") {
      o.ideal = true;
    } else if (arg == "--log-motion") {
      o.log_motion = true;
    } else if (arg == "--strict") {
      o.strict = true;
    } else if (arg == "--map" || arg == "--robot" || arg == "--link") {
      if (!value(v) || v.empty())
        return arg + " needs a path";
      if (arg == "--map")
        o.map = v;
      else if (arg == "--robot")
        o.robot = v;
      else
        o.link = v;
    } else if (arg == "--seed" || arg == "--tcp" || arg == "--baud") {
      if (!value(v) || !parseNumber(v, number) || number < 0 || number != std::floor(number))
        return arg + " needs a non-negative integer";
      if (arg == "--seed") {
        o.seed = static_cast<std::uint64_t>(number);
      } else if (arg == "--tcp") {
        if (number > 65535)
          return "--tcp: port must be 0-65535";
        o.tcp_port = static_cast<std::uint16_t>(number);
      } else {
        if (number < 300 || number > 4000000)
          return "--baud: must be 300-4000000";
        o.baud = static_cast<std::uint32_t>(number);
      }
    } else if (arg == "--protocol") {
      if (!value(v) || (v != "mavlink" && v != "arcos"))
        return "--protocol needs mavlink or arcos";
      o.arcos = v == "arcos";
    } else if (arg == "--watchdog") {
      if (!value(v) || !parseNumber(v, number) || number <= 0 || number > 1000)
        return arg + " needs a positive number";
      o.watchdog_s = number;
    } else if (arg == "--rate" || arg == "--gcs-timeout") {
      if (!value(v) || !parseNumber(v, number) || number <= 0 || number > 1000)
        return arg + " needs a positive number";
      (arg == "--rate" ? o.rate_hz : o.gcs_timeout_s) = number;
    } else {
      return "unknown option " + arg;
    }
  }
  if (pty && o.tcp_port)
    return "--pty and --tcp exclude each other";
  if (!o.link.empty() && o.tcp_port)
    return "--link needs the pty transport";
  if (o.strict && !o.arcos)
    return "--strict is for --protocol arcos (the virtual Pioneer)";
  return {};
}

speed_t termiosSpeed(std::uint32_t baud) {
  switch (baud) {
    case 9600:
      return B9600;
    case 19200:
      return B19200;
    case 38400:
      return B38400;
    case 57600:
      return B57600;
    case 230400:
      return B230400;
    case 460800:
      return B460800;
    case 921600:
      return B921600;
    default:
      return B115200;
  }
}

// The master side of a pseudo-terminal, polled on every tick (non-blocking). read() gives EIO
// while no program holds the slave open: then nothing is written, so a ground station that
// opens the port later does not first receive seconds of stale telemetry.
class PtyLink {
 public:
  explicit PtyLink(std::uint32_t baud) : bytes_per_s_(baud / 10.0) {}
  ~PtyLink() {
    if (fd_ >= 0)
      ::close(fd_);
  }

  std::string open(std::uint32_t baud) {
    fd_ = ::posix_openpt(O_RDWR | O_NOCTTY | O_NONBLOCK);
    if (fd_ < 0 || ::grantpt(fd_) != 0 || ::unlockpt(fd_) != 0)
      return std::string("cannot open a pseudo-terminal: ") + std::strerror(errno);
    termios tio{};
    if (::tcgetattr(fd_, &tio) == 0) {
      ::cfmakeraw(&tio);  // no echo, no line discipline: a clean 8-bit byte pipe
      ::cfsetispeed(&tio, termiosSpeed(baud));
      ::cfsetospeed(&tio, termiosSpeed(baud));
      ::tcsetattr(fd_, TCSANOW, &tio);
    }
    const char* name = ::ptsname(fd_);
    if (name == nullptr)
      return "ptsname failed";
    path_ = name;
    return {};
  }
  const std::string& path() const { return path_; }

  // Reads everything available into `out`; returns false when no program has the slave open.
  bool poll(std::vector<std::uint8_t>& out) {
    std::uint8_t buf[4096];
    for (;;) {
      const ssize_t n = ::read(fd_, buf, sizeof buf);
      if (n > 0) {
        out.insert(out.end(), buf, buf + n);
        continue;
      }
      if (n < 0 && errno == EINTR)
        continue;
      peer_ = !(n < 0 && errno == EIO);
      return peer_;
    }
  }

  // Queues frames and writes at most the baud rate allows. Whole chunks are dropped when the
  // queue already holds a quarter second of output (a real UART link would fall behind too).
  void write(const std::vector<std::uint8_t>& bytes, double elapsed_s) {
    if (!peer_) {
      pending_.clear();
      budget_ = 0.0;
      return;
    }
    if (pending_.size() + bytes.size() <= static_cast<std::size_t>(bytes_per_s_ * 0.25) + 512)
      pending_.insert(pending_.end(), bytes.begin(), bytes.end());
    budget_ = std::min(budget_ + elapsed_s * bytes_per_s_, bytes_per_s_ * 0.05 + 512);
    const std::size_t allowed = std::min(pending_.size(), static_cast<std::size_t>(budget_));
    if (allowed == 0)
      return;
    const ssize_t n = ::write(fd_, pending_.data(), allowed);
    if (n > 0) {
      pending_.erase(pending_.begin(), pending_.begin() + n);
      budget_ -= static_cast<double>(n);
    }
  }

 private:
  int fd_ = -1;
  std::string path_;
  bool peer_ = false;
  double bytes_per_s_;
  double budget_ = 0.0;
  std::vector<std::uint8_t> pending_;
};

// What the ground station sent, as it arrived: the end-to-end tests read the peak per second.
void printWireSummary(const irgs::app::FirmwareCore* core, const irgs::app::ArcosFirmware* arcos,
                      const irgs::app::ArrivalRateMeter& manual_controls) {
  if (core) {
    std::printf("wire: MANUAL_CONTROL %s\n", manual_controls.summary().c_str());
  } else if (arcos) {
    const irgs::app::ArcosFirmwareStats& s = arcos->stats();
    std::printf(
        "wire: ARCOS command packets %s; taken %llu, lost too soon %llu, malformed %llu, "
        "unknown %llu, watchdog stops %u%s\n",
        arcos->commandRate().summary().c_str(), static_cast<unsigned long long>(s.commands),
        static_cast<unsigned long long>(s.too_soon),
        static_cast<unsigned long long>(s.bad_commands),
        static_cast<unsigned long long>(s.unknown_commands), s.watchdog_stops,
        arcos->config().strict ? " (strict)" : "");
  }
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  bool help = false;
  const std::string error = parseOptions(argc, argv, options, help);
  if (help) {
    std::fputs(kUsage, stdout);
    return 0;
  }
  if (!error.empty()) {
    std::fprintf(stderr, "irgs-robot: %s\n%s", error.c_str(), kUsage);
    return kExitUsage;
  }

  auto map = irgs::loadAnyMap(options.map);
  for (const auto& d : map.diagnostics)
    std::fprintf(stderr, "%s\n", d.toString().c_str());
  if (!map.map) {
    std::fprintf(stderr, "irgs-robot: cannot load map %s\n", options.map.string().c_str());
    return kExitFiles;
  }
  auto robot = irgs::loadRobotProfileFile(options.robot);
  for (const auto& d : robot.diagnostics)
    std::fprintf(stderr, "%s\n", d.toString().c_str());
  if (!robot.profile) {
    std::fprintf(stderr, "irgs-robot: cannot load robot %s\n", options.robot.string().c_str());
    return kExitFiles;
  }

  irgs::SimConfig sim_config;
  sim_config.seed = options.seed;
  sim_config =
      options.ideal ? irgs::idealSimConfig(sim_config) : irgs::typicalSimConfig(sim_config);
  // A yaw-rate gyro at the AUTOGYRO level of paper 001, as in the GUI's simulator: SCALED_IMU
  // then carries its raw rate and temperature, so the encoder + gyro filter works over the link.
  if (!options.ideal)
    sim_config.gyro = irgs::autogyroErrorModel();
  // Below 38400 baud the full telemetry does not fit: use the compact dialect profile.
  irgs::app::FirmwareConfig fw_config;
  if (options.baud < 38400 && !options.tcp_port) {
    fw_config = irgs::app::slowLinkFirmwareConfig();
  } else {
    fw_config.odometry_period_s = 1.0 / options.rate_hz;
    fw_config.sonar_period_s = 1.0 / options.rate_hz;
  }
  fw_config.gcs_timeout_s = options.gcs_timeout_s;
  std::unique_ptr<irgs::app::FirmwareCore> core;
  std::unique_ptr<irgs::app::ArcosFirmware> arcos;  // --protocol arcos
  try {
    irgs::Simulator sim(std::move(*map.map), std::move(*robot.profile), sim_config);
    if (options.arcos) {
      irgs::app::ArcosFirmwareConfig arcos_config;
      arcos_config.watchdog_s = options.watchdog_s;
      arcos_config.strict = options.strict;
      if (!options.tcp_port)
        arcos_config.link_baud = options.baud;  // the pty is paced like a UART at this baud
      arcos = std::make_unique<irgs::app::ArcosFirmware>(std::move(sim), arcos_config);
    } else {
      core = std::make_unique<irgs::app::FirmwareCore>(std::move(sim), fw_config);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "irgs-robot: %s\n", e.what());
    return kExitFiles;
  }
  // What arrives on the wire, for the summary on exit: MAVLink's MANUAL_CONTROLs are counted
  // here (ARCOS command packets by ArcosFirmware).
  irgs::comms::mavlink::FrameDecoder tap;
  std::vector<irgs::comms::mavlink::Frame> tapped;
  irgs::app::ArrivalRateMeter manual_controls;
  // The served protocol, whichever it is.
  const auto receive = [&](std::span<const std::uint8_t> bytes, double now_s) {
    if (core) {
      tapped.clear();
      tap.feed(bytes, tapped);
      for (const auto& frame : tapped) {
        if (frame.message_id == irgs::comms::mavlink::ManualControl::kId)
          manual_controls.record(now_s);
      }
      core->receiveBytes(bytes, now_s);
    } else {
      arcos->receiveBytes(bytes, now_s);
    }
  };
  const auto advance = [&core, &arcos](double now_s) {
    core ? core->advance(now_s) : arcos->advance(now_s);
  };
  const auto takeOutput = [&core, &arcos] {
    return core ? core->takeOutput() : arcos->takeOutput();
  };
  const irgs::Simulator& simulator = core ? core->simulator() : arcos->simulator();
  const double dt = simulator.config().dt_s;

  // Signals are taken by sigtimedwait in this thread; block them before the io thread starts so
  // it inherits the mask.
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);
  ::signal(SIGPIPE, SIG_IGN);

  std::unique_ptr<PtyLink> pty;
  if (!options.tcp_port) {
    pty = std::make_unique<PtyLink>(options.baud);
    const std::string pty_error = pty->open(options.baud);
    if (!pty_error.empty()) {
      std::fprintf(stderr, "irgs-robot: %s\n", pty_error.c_str());
      return kExitIo;
    }
    if (!options.link.empty()) {
      std::error_code ec;
      if (fs::is_symlink(options.link, ec))
        fs::remove(options.link, ec);
      fs::create_symlink(pty->path(), options.link, ec);
      if (ec) {
        std::fprintf(stderr, "irgs-robot: cannot create link %s: %s\n", options.link.c_str(),
                     ec.message().c_str());
        return kExitIo;
      }
    }
    std::printf("%s\n", pty->path().c_str());
    std::fflush(stdout);
  }

  std::atomic<bool> fatal{false};
  {
    // Explicit lifetimes: the io thread is joined (io.reset()) before the state its handlers
    // use goes away, and the timer and transport are destroyed on the io thread before that.
    auto io = std::make_unique<irgs::comms::IoThread>();
    std::unique_ptr<irgs::comms::Transport> tcp;
    auto timer = std::make_unique<boost::asio::steady_timer>(io->context());
    const Clock::time_point start = Clock::now();
    auto seconds = [start](Clock::time_point t) {
      return std::chrono::duration<double>(t - start).count();
    };

    if (options.tcp_port) {
      irgs::comms::TcpServerOptions tcp_options;
      tcp_options.port = *options.tcp_port;
      irgs::comms::TransportCallbacks callbacks;
      callbacks.on_bytes = [&receive, &seconds](std::span<const std::uint8_t> bytes) {
        receive(bytes, seconds(Clock::now()));
      };
      // Announce the port once it is bound (the second `opening` report: "listening on ...").
      callbacks.on_state = [&fatal, &tcp, announced = false](irgs::comms::TransportState state,
                                                             const std::string& message) mutable {
        if (state == irgs::comms::TransportState::kFailed) {
          std::fprintf(stderr, "irgs-robot: tcp: %s\n", message.c_str());
          fatal = true;
        } else if (!announced && tcp && tcp->localPort() != 0) {
          std::printf("tcp %u\n", static_cast<unsigned>(tcp->localPort()));
          std::fflush(stdout);
          announced = true;
        }
      };
      tcp = irgs::comms::makeTcpServerTransport(*io, tcp_options, callbacks);
      boost::asio::post(io->context(), [&tcp] { tcp->open(); });
    }

    // The stepping loop: every dt of wall time, read, advance the simulator to now, write.
    std::vector<std::uint8_t> rx;
    Clock::time_point next = start;
    Clock::time_point last_write = start;
    bool was_moving = false;  // --log-motion
    // Set on the io thread at shutdown: a timer completion already queued when the timer is
    // destroyed still runs (with success), and must not touch the destroyed timer.
    bool stopping = false;
    std::function<void()> tick = [&] {
      if (stopping)
        return;
      const Clock::time_point now = Clock::now();
      const double now_s = seconds(now);
      if (pty) {
        rx.clear();
        pty->poll(rx);
        if (!rx.empty())
          receive(rx, now_s);
      }
      advance(now_s);
      if (options.log_motion) {
        const irgs::VelocityCommand v = simulator.trueVelocity();
        const bool moving = std::abs(v.linear_mps) > 1e-4 || std::abs(v.angular_radps) > 1e-4;
        if (moving != was_moving) {
          was_moving = moving;
          std::printf("motion %s t=%.3f mono=%.6f\n", moving ? "start" : "stop", now_s,
                      std::chrono::duration<double>(now.time_since_epoch()).count());
          std::fflush(stdout);
        }
      }
      const std::vector<std::uint8_t> out = takeOutput();
      if (pty) {
        pty->write(out, std::chrono::duration<double>(now - last_write).count());
      } else if (tcp && !out.empty()) {
        tcp->send(out);  // refused (and counted) while no client is connected
      }
      last_write = now;
      next += std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(dt));
      if (next < now - std::chrono::milliseconds(200))
        next = now;  // suspended or overloaded: do not race to catch up the timer
      timer->expires_at(next);
      timer->async_wait([&tick](const boost::system::error_code& ec) {
        if (!ec)
          tick();
      });
    };
    boost::asio::post(io->context(), tick);

    for (;;) {
      timespec wait{0, 100'000'000};
      const int sig = sigtimedwait(&signals, nullptr, &wait);
      if (sig == SIGINT || sig == SIGTERM || fatal)
        break;
    }
    std::promise<void> stopped;
    boost::asio::post(io->context(), [&] {
      stopping = true;
      timer.reset();
      tcp.reset();
      stopped.set_value();
    });
    stopped.get_future().wait();
    io.reset();
  }
  printWireSummary(core.get(), arcos.get(), manual_controls);
  if (!options.link.empty()) {
    std::error_code ec;
    if (fs::is_symlink(options.link, ec) && pty &&
        fs::read_symlink(options.link, ec) == pty->path())
      fs::remove(options.link, ec);
  }
  return fatal ? kExitIo : 0;
}
