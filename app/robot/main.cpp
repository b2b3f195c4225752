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
#include "app/robot/drive_guard.hpp"
#include "app/robot/firmware_core.hpp"
#include "comms/mavlink/frame_decoder.hpp"
#include "comms/mavlink/messages.hpp"
#include "comms/mavlink/signing_key.hpp"
#include "comms/transport/io_thread.hpp"
#include "comms/transport/tcp_transport.hpp"
#include "comms/transport/udp_transport.hpp"
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
    "                  [--tcp [ADDR:]PORT | --udp [ADDR:]PORT] [--signing-key FILE]\n"
    "                  [--baud N] [--rate HZ] [--gcs-timeout S] [--ideal]\n"
    "                  [--log-motion] [--protocol mavlink|arcos] [--watchdog S] [--strict]\n"
    "  Serves the simulated robot over MAVLink 2. Without --tcp or --udp it opens a\n"
    "  pseudo-terminal, prints its path (/dev/pts/N) on stdout and serves on it; --link PATH\n"
    "  also creates a symlink PATH to it. --tcp [ADDR:]PORT serves as a TCP server (0 = any\n"
    "  free port; the port is printed as 'tcp PORT'), --udp [ADDR:]PORT as a UDP listener that\n"
    "  answers the ground station that sent first (printed as 'udp PORT'). Both bind ADDR,\n"
    "  by default 127.0.0.1 (this computer only); 0.0.0.0 serves every interface.\n"
    "  One ground station drives: while it is active (heartbeats within --gcs-timeout) a second\n"
    "  one is refused (TCP: its connection closed; UDP: its datagrams dropped), counted, named\n"
    "  to the first in a STATUSTEXT warning and on stderr (ARCOS: stderr only).\n"
    "  --signing-key FILE: MAVLink 2 signing with the key in FILE (64 hex digits; the GUI's\n"
    "  connection dialog exports one). Everything sent is signed; unsigned, wrongly signed and\n"
    "  replayed frames are refused, counted (SYS_STATUS errors_comm) and reported (STATUSTEXT\n"
    "  and stderr, at most every 5 s). The key's fingerprint is printed on stderr.\n"
    "  --baud N limits the pty output to N/10 bytes/s like a UART\n"
    "  (default 115200); below 38400 the compact profile is sent (IRGS_POSE_2D 10 Hz,\n"
    "  IRGS_SONAR_SCAN 5 Hz), also over --tcp/--udp (a bridge to a serial link: only the pty\n"
    "  is paced; strict ARCOS takes the packets of one read as that link delivered them, one\n"
    "  after the other at its byte time). --rate HZ: odometry and sonar telemetry rate\n"
    "  (default 20).\n"
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

// A listening endpoint from --tcp / --udp: "PORT" or "ADDR:PORT".
struct ListenSpec {
  bool udp = false;
  std::string host;  // empty: loopback
  std::uint16_t port = 0;
};

struct Options {
  fs::path map = fs::path(IRGS_RESOURCE_DIR) / "maps/default.json";
  fs::path robot = fs::path(IRGS_RESOURCE_DIR) / "robots/thesis_robot.json";
  std::uint64_t seed = 1;
  std::optional<ListenSpec> listen;  // --tcp / --udp
  fs::path signing_key;              // --signing-key
  std::string link;
  std::uint32_t baud = 115200;
  bool baud_given = false;  // --baud: over --tcp/--udp, the serial link behind a bridge
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

// "PORT" or "ADDR:PORT" (ADDR an IPv4 address: checked when the transport binds it).
std::optional<ListenSpec> parseListen(const std::string& text, bool udp) {
  ListenSpec spec;
  spec.udp = udp;
  std::string port = text;
  if (const auto colon = text.rfind(':'); colon != std::string::npos) {
    spec.host = text.substr(0, colon);
    port = text.substr(colon + 1);
    if (spec.host.empty())
      return std::nullopt;
  }
  double number = 0.0;
  if (!parseNumber(port, number) || number < 0 || number > 65535 || number != std::floor(number))
    return std::nullopt;
  spec.port = static_cast<std::uint16_t>(number);
  return spec;
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
    } else if (arg == "--map" || arg == "--robot" || arg == "--link" || arg == "--signing-key") {
      if (!value(v) || v.empty())
        return arg + " needs a path";
      if (arg == "--map")
        o.map = v;
      else if (arg == "--robot")
        o.robot = v;
      else if (arg == "--signing-key")
        o.signing_key = v;
      else
        o.link = v;
    } else if (arg == "--tcp" || arg == "--udp") {
      if (o.listen)
        return "give one of --tcp and --udp, once";
      if (value(v))
        o.listen = parseListen(v, arg == "--udp");
      if (!o.listen)
        return arg + " needs PORT or ADDR:PORT (port 0-65535), e.g. 5760 or 0.0.0.0:5760";
    } else if (arg == "--seed" || arg == "--baud") {
      if (!value(v) || !parseNumber(v, number) || number < 0 || number != std::floor(number))
        return arg + " needs a non-negative integer";
      if (arg == "--seed") {
        o.seed = static_cast<std::uint64_t>(number);
      } else {
        if (number < 300 || number > 4000000)
          return "--baud: must be 300-4000000";
        o.baud = static_cast<std::uint32_t>(number);
        o.baud_given = true;
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
  if (pty && o.listen)
    return "--pty excludes --tcp and --udp";
  if (!o.link.empty() && o.listen)
    return "--link needs the pty transport";
  if (!o.signing_key.empty() && o.arcos)
    return "--signing-key is MAVLink's: ARCOS has no signing";
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

// What the --tcp / --udp transport needs from the served protocol; called on the io thread.
struct ListenerHooks {
  std::function<double()> now_s;
  std::function<void(std::span<const std::uint8_t> bytes, double now_s)> receive;
  std::function<bool(double now_s)> peer_alive;         // the attached peer, by the protocol
  std::function<void(const std::string& text)> report;  // a refusal report
  std::function<std::vector<std::uint8_t>(const std::string& peer)> refusal_bytes;  // optional
};

// The --tcp / --udp transport (closed) with its "who may drive" policy: comms::PeerPolicy asks
// the guard, which keeps the attached ground station while it is alive. Prints "tcp PORT" or
// "udp PORT" once bound; a failure is printed and sets `fatal`.
std::unique_ptr<irgs::comms::Transport> makeListener(irgs::comms::IoThread& io,
                                                     const ListenSpec& spec,
                                                     irgs::app::DriveGuard& guard,
                                                     ListenerHooks hooks_value,
                                                     std::atomic<bool>& fatal) {
  namespace comms = irgs::comms;
  const auto hooks = std::make_shared<const ListenerHooks>(std::move(hooks_value));
  comms::PeerPolicy peers;
  peers.peer_active = [hooks, &guard] {
    const double now_s = hooks->now_s();
    return guard.peerActive(now_s, hooks->peer_alive(now_s));
  };
  peers.refusal_bytes = hooks->refusal_bytes;
  // Set once the transport exists (its callbacks run only after open()).
  const auto transport = std::make_shared<comms::Transport*>(nullptr);
  comms::TransportCallbacks callbacks;
  callbacks.on_bytes = [hooks, &guard](std::span<const std::uint8_t> bytes) {
    const double now_s = hooks->now_s();
    guard.peerBytes(now_s);  // UDP: the first datagram of a new peer attaches it
    hooks->receive(bytes, now_s);
  };
  callbacks.on_refused = [hooks, &guard](const std::string& peer) {
    if (auto report = guard.refused(peer, hooks->now_s()))
      hooks->report(*report);
  };
  const std::string kind = spec.udp ? "udp" : "tcp";
  callbacks.on_state = [hooks, &guard, &fatal, transport, kind, announced = false](
                           comms::TransportState state, const std::string& message) mutable {
    if (state == comms::TransportState::kFailed) {
      std::fprintf(stderr, "irgs-robot: %s: %s\n", kind.c_str(), message.c_str());
      fatal = true;
      return;
    }
    if (state == comms::TransportState::kOpen && kind == "tcp")
      guard.peerAttached(hooks->now_s());  // a client connected
    // Announce the port once it is bound ("listening on ..." / "bound udp ...").
    if (!announced && *transport && (*transport)->localPort() != 0) {
      std::printf("%s %u\n", kind.c_str(), static_cast<unsigned>((*transport)->localPort()));
      std::fflush(stdout);
      announced = true;
    }
  };
  std::unique_ptr<comms::Transport> made;
  if (spec.udp) {
    comms::UdpOptions o;
    o.listen = true;
    o.host = spec.host;
    o.port = spec.port;
    o.peers = std::move(peers);
    made = comms::makeUdpTransport(io, std::move(o), std::move(callbacks));
  } else {
    comms::TcpServerOptions o;
    o.host = spec.host;
    o.port = spec.port;
    o.peers = std::move(peers);
    made = comms::makeTcpServerTransport(io, std::move(o), std::move(callbacks));
  }
  *transport = made.get();
  return made;
}

// What a refused MAVLink ground station reads before its connection closes: a STATUSTEXT from
// the robot's ids (signed with the key, on a link id of its own, so a signing ground station
// shows it too).
std::function<std::vector<std::uint8_t>(const std::string&)> mavlinkRefusal(
    const irgs::app::FirmwareConfig& config) {
  namespace mav = irgs::comms::mavlink;
  auto encoder = std::make_shared<mav::FrameEncoder>(config.system_id, config.component_id);
  if (config.signing_key)
    encoder->enableSigning(*config.signing_key, /*link_id=*/1);
  return [encoder](const std::string&) {
    mav::Statustext m;
    m.severity = static_cast<std::uint8_t>(mav::MavSeverity::kWarning);
    const std::string text = "busy: another ground station is driving";
    std::copy(text.begin(), text.end(), m.text.begin());
    const mav::EncodedFrame frame =
        encoder->encode(m, mav::signingTimestampAt(std::chrono::system_clock::now()));
    const auto bytes = frame.view();
    return std::vector<std::uint8_t>(bytes.begin(), bytes.end());
  };
}

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
  // Below 38400 baud the full telemetry does not fit: use the compact dialect profile (over
  // TCP/UDP too, where --baud names the serial link behind a bridge).
  irgs::app::FirmwareConfig fw_config;
  if (options.baud < 38400) {
    fw_config = irgs::app::slowLinkFirmwareConfig();
  } else {
    fw_config.odometry_period_s = 1.0 / options.rate_hz;
    fw_config.sonar_period_s = 1.0 / options.rate_hz;
  }
  fw_config.gcs_timeout_s = options.gcs_timeout_s;
  if (!options.signing_key.empty()) {
    const irgs::comms::mavlink::SigningKeyResult key =
        irgs::comms::mavlink::loadSigningKeyFile(options.signing_key);
    if (!key.key) {
      std::fprintf(stderr, "irgs-robot: %s\n", key.error.c_str());
      return kExitFiles;
    }
    fw_config.signing_key = key.key;
    fw_config.signing_time_at_boot =
        irgs::comms::mavlink::signingTimestampAt(std::chrono::system_clock::now());
    std::fprintf(stderr,
                 "irgs-robot: MAVLink signing on, key fingerprint %s: unsigned commands are "
                 "refused\n",
                 irgs::comms::mavlink::signingKeyFingerprint(*key.key).c_str());
  }
  std::unique_ptr<irgs::app::FirmwareCore> core;
  std::unique_ptr<irgs::app::ArcosFirmware> arcos;  // --protocol arcos
  try {
    irgs::Simulator sim(std::move(*map.map), std::move(*robot.profile), sim_config);
    if (options.arcos) {
      irgs::app::ArcosFirmwareConfig arcos_config;
      arcos_config.watchdog_s = options.watchdog_s;
      arcos_config.strict = options.strict;
      // The pty is paced like a UART at this baud; over TCP/UDP an explicit --baud names the
      // serial line behind the bridge, whose bytes came one after the other at that pace.
      if (!options.listen || options.baud_given)
        arcos_config.link_baud = options.baud;
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
  // earliest_s: the bytes may have arrived any time since (the previous poll of the pty).
  const auto receive = [&](std::span<const std::uint8_t> bytes, double now_s,
                           std::optional<double> earliest_s = std::nullopt) {
    if (core) {
      tapped.clear();
      tap.feed(bytes, tapped);
      for (const auto& frame : tapped) {
        if (frame.message_id == irgs::comms::mavlink::ManualControl::kId)
          manual_controls.record(now_s);
      }
      core->receiveBytes(bytes, now_s);
    } else {
      arcos->receiveBytes(bytes, now_s, earliest_s);
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
  if (!options.listen) {
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
    std::unique_ptr<irgs::comms::Transport> listener;  // --tcp / --udp
    double last_rx_s = -1e9;                           // newest bytes from the listener's peer
    auto timer = std::make_unique<boost::asio::steady_timer>(io->context());
    const Clock::time_point start = Clock::now();
    auto seconds = [start](Clock::time_point t) {
      return std::chrono::duration<double>(t - start).count();
    };

    // Who may drive (--tcp / --udp): refusals are reported on stderr and, over MAVLink, to the
    // ground station that drives (STATUSTEXT). Everything here runs on the io thread.
    irgs::app::DriveGuard guard(options.arcos ? options.watchdog_s.value_or(2.0)
                                              : options.gcs_timeout_s);
    const auto reportRefusals = [&core](const std::string& text) {
      std::fprintf(stderr, "irgs-robot: %s\n", text.c_str());
      if (core)
        core->warnGroundStation(text);
    };
    if (options.listen) {
      ListenerHooks hooks;
      hooks.now_s = [&seconds] { return seconds(Clock::now()); };
      hooks.receive = [&receive, &last_rx_s](std::span<const std::uint8_t> bytes, double now_s) {
        last_rx_s = now_s;
        receive(bytes, now_s);
      };
      hooks.peer_alive = [&core, &last_rx_s, &options](double now_s) {
        if (core)
          return core->safety().gcs_alive;  // a heartbeat (signed, with a key) within timeout
        return now_s - last_rx_s < options.watchdog_s.value_or(2.0);  // ARCOS: any packet
      };
      hooks.report = reportRefusals;
      if (core)
        hooks.refusal_bytes = mavlinkRefusal(fw_config);
      listener = makeListener(*io, *options.listen, guard, std::move(hooks), fatal);
      boost::asio::post(io->context(), [&listener] { listener->open(); });
    }

    // The pty is read on every tick, and in strict ARCOS mode also every millisecond, like the
    // Pioneer's command processor: how close two commands came is then measured to a
    // millisecond, not to the 10 ms of a simulator step.
    std::vector<std::uint8_t> rx;
    std::optional<double> last_poll_s;
    const auto pollPty = [&](double now_s) {
      rx.clear();
      pty->poll(rx);
      if (!rx.empty())
        receive(rx, now_s, last_poll_s);
      last_poll_s = now_s;
    };
    auto poll_timer = std::make_unique<boost::asio::steady_timer>(io->context());

    // The stepping loop: every dt of wall time, read, advance the simulator to now, write.
    Clock::time_point next = start;
    Clock::time_point last_write = start;
    bool was_moving = false;                   // --log-motion
    std::uint64_t refused_frames_printed = 0;  // --signing-key: refusals on stderr, every 5 s
    double next_refused_print_s = 0.0;
    // Set on the io thread at shutdown: a timer completion already queued when the timer is
    // destroyed still runs (with success), and must not touch the destroyed timer.
    bool stopping = false;
    std::function<void()> fast_poll = [&] {
      if (stopping)
        return;
      pollPty(seconds(Clock::now()));
      poll_timer->expires_after(std::chrono::milliseconds(1));
      poll_timer->async_wait([&fast_poll](const boost::system::error_code& ec) {
        if (!ec)
          fast_poll();
      });
    };
    std::function<void()> tick = [&] {
      if (stopping)
        return;
      const Clock::time_point now = Clock::now();
      const double now_s = seconds(now);
      if (pty)
        pollPty(now_s);
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
      } else if (listener && !out.empty()) {
        listener->send(out);  // refused (and counted) while no ground station is attached
      }
      if (auto report = guard.dueReport(now_s))
        reportRefusals(*report);
      if (core && core->refusedFrames() != refused_frames_printed &&
          now_s >= next_refused_print_s) {
        // The firmware tells the ground station (STATUSTEXT); this is the robot's own log.
        refused_frames_printed = core->refusedFrames();
        next_refused_print_s = now_s + irgs::app::DriveGuard::kDefaultReportPeriod_s;
        const irgs::comms::mavlink::DecodeCounters& totals = core->decodeTotals();
        std::fprintf(stderr,
                     "irgs-robot: signing: %llu frames refused (unsigned %llu, bad signature "
                     "%llu, replayed %llu)\n",
                     static_cast<unsigned long long>(refused_frames_printed),
                     static_cast<unsigned long long>(totals.unsigned_rejected),
                     static_cast<unsigned long long>(totals.bad_signature),
                     static_cast<unsigned long long>(totals.replay_rejected));
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
    if (pty && options.strict)
      boost::asio::post(io->context(), fast_poll);

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
      poll_timer.reset();
      listener.reset();
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
