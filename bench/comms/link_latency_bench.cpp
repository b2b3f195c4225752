// irgs_bench_link_latency: end-to-end latency "from a robot sample to the GUI's model" over a
// real pty at 115200 baud. The virtual robot firmware (FirmwareCore, the core of irgs-robot)
// runs in-process on the master side of a pty pair with its output paced like a UART
// (11520 B/s, the full telemetry set, ~89 % of the link); LinkedRobot opens the slave as
// serial://...?baud=115200 and a loop drains update() at ~60 Hz as the GUI does. For every sample
// that comes out of update() the latency is the wall time since the firmware started writing the
// step that carries its odometry (LOCAL_POSITION_NED) to the pty. Both sample-assembly modes are
// measured (docs/protocol.md, "Linked robot"): by time stamp (the default: a sample waits for its
// sonar readings) and release on pose. Not a Google Benchmark: the quantity is a wall-clock
// distribution, not a loop time. Usage: irgs_bench_link_latency [--seconds S] (default 20 per
// mode). Results: docs/performance.md.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>
#include <vector>

#include "comms/robot/linked_robot.hpp"
#include "comms/transport/io_thread.hpp"
#include "tests/comms/robot/firmware_pty_server.hpp"
#include "tests/comms/robot/robot_test_support.hpp"

namespace {

using namespace irgs;
using namespace irgs::comms;
using Clock = std::chrono::steady_clock;

constexpr double kFramePeriod_s = 1.015 / 60.0;

struct Measurement {
  std::vector<double> latency_ms;
  std::size_t samples = 0;
  std::size_t unmatched = 0;
  double robot_span_s = 0.0;
  std::uint64_t dropped_bytes = 0;
};

double percentile(std::vector<double> v, double p) {
  if (v.empty())
    return 0.0;
  std::sort(v.begin(), v.end());
  const double rank = p / 100.0 * static_cast<double>(v.size() - 1);
  const auto lo = static_cast<std::size_t>(std::floor(rank));
  const auto hi = std::min(lo + 1, v.size() - 1);
  return v[lo] + (v[hi] - v[lo]) * (rank - static_cast<double>(lo));
}

// Returns false (with a message) when the link never came up.
bool measure(bool release_on_pose, double seconds, Measurement& m) {
  testing::FirmwarePtyServer server(testing::makeFirmware({}, false, 11),
                                    {.bytes_per_s = 11520.0, .symlink = {}});
  IoThread io;
  LinkedRobotConfig config;
  config.telemetry.release_on_pose = release_on_pose;
  auto url = parseLinkUrl("serial://" + server.slavePath() + "?baud=115200");
  auto opened = LinkedRobot::open(io, *url.url, testing::thesisRobot(), config);
  if (!opened.robot) {
    std::fprintf(stderr, "irgs_bench_link_latency: %s\n", opened.error.c_str());
    return false;
  }
  LinkedRobot& robot = *opened.robot;
  // A 60 Hz display is not locked to the robot's clock, so the phase between the frames and the
  // 20 Hz telemetry wanders. Here both loops run on the same PC clock and 50 ms is exactly three
  // 16.7 ms frames: at exactly 60 Hz the phase would freeze and the result would depend on the
  // start-up phase. The frame period is therefore detuned by 1.5 % (59.1 Hz): the phase sweeps the
  // whole frame about once a second, which is what an unlocked display does on average.
  const auto period =
      std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(kFramePeriod_s));
  // Connect (deadline 10 s), then drive a slow circle so the link carries motion telemetry.
  const Clock::time_point connect_deadline = Clock::now() + std::chrono::seconds(10);
  while (robot.linkState() != LinkState::kConnected) {
    if (Clock::now() > connect_deadline) {
      std::fprintf(stderr, "irgs_bench_link_latency: the link never came up\n");
      return false;
    }
    robot.update(0.0);
    std::this_thread::sleep_for(period);
  }
  robot.drive({0.15, 0.5});
  const Clock::time_point start = Clock::now();
  const Clock::time_point warm = start + std::chrono::seconds(1);
  const Clock::time_point end =
      warm + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
  Clock::time_point next = start;
  double first_s = -1.0, last_s = 0.0;
  while (Clock::now() < end) {
    next += period;
    std::this_thread::sleep_until(next);  // the GUI's frame
    const auto samples = robot.update(kFramePeriod_s);
    const Clock::time_point now = Clock::now();
    if (now < warm)
      continue;
    for (const auto& s : samples) {
      const auto emitted = server.emittedAt(std::llround(s.time_s * 1000.0));
      ++m.samples;
      if (!emitted) {
        ++m.unmatched;
        continue;
      }
      m.latency_ms.push_back(std::chrono::duration<double, std::milli>(now - *emitted).count());
      if (first_s < 0)
        first_s = s.time_s;
      last_s = s.time_s;
    }
  }
  robot.stop();
  m.robot_span_s = last_s - first_s;
  m.dropped_bytes = server.droppedBytes();
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  double seconds = 20.0;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--seconds" && i + 1 < argc) {
      seconds = std::atof(argv[++i]);
    } else {
      std::fprintf(stderr, "usage: irgs_bench_link_latency [--seconds S]\n");
      return 2;
    }
  }
  if (!(seconds > 0.0) || seconds > 3600.0) {
    std::fprintf(stderr, "irgs_bench_link_latency: --seconds must be in (0, 3600]\n");
    return 2;
  }
  std::printf(
      "robot sample -> LinkedRobot::update() at %.1f Hz, pty at 115200 baud (11520 B/s "
      "paced), %.0f s per mode\n",
      1.0 / kFramePeriod_s, seconds);
  std::printf("%-18s %8s %9s %8s %8s %8s %8s %8s\n", "assembly", "samples", "rate_Hz", "p50_ms",
              "p90_ms", "p99_ms", "max_ms", "dropB");
  for (const bool on_pose : {false, true}) {
    Measurement m;
    if (!measure(on_pose, seconds, m))
      return 1;
    if (m.latency_ms.empty()) {
      std::fprintf(stderr, "irgs_bench_link_latency: no samples measured\n");
      return 1;
    }
    const double rate =
        m.robot_span_s > 0 ? static_cast<double>(m.latency_ms.size() - 1) / m.robot_span_s : 0.0;
    std::printf("%-18s %8zu %9.1f %8.1f %8.1f %8.1f %8.1f %8llu\n",
                on_pose ? "release-on-pose" : "by-timestamp", m.latency_ms.size(), rate,
                percentile(m.latency_ms, 50), percentile(m.latency_ms, 90),
                percentile(m.latency_ms, 99),
                *std::max_element(m.latency_ms.begin(), m.latency_ms.end()),
                static_cast<unsigned long long>(m.dropped_bytes));
    if (m.unmatched > 0)
      std::printf("  (%zu samples without a recorded emission time)\n", m.unmatched);
  }
  return 0;
}
