// FrameDecoder throughput on the mixed telemetry stream of issue 3 (per 50 ms tick: HEARTBEAT,
// 8 DISTANCE_SENSOR, ODOMETRY, SCALED_IMU; see decoder_bench_stream.hpp), in bytes per second.
//
//   BM_FrameDecoder/CHUNK        framing + CRC_EXTRA check + sequence tracking, the stream fed
//                                in CHUNK-byte reads (64: a busy UART read, 4096: a socket read)
//   BM_FrameDecoderUnpack/CHUNK  the same plus unpacking every frame into its typed message
//
// The reference, node-mavlink 2.3.0 parsing the same bytes, runs in node; the driver script
// bench/comms/run_decoder_compare.sh writes the stream once (--write-stream FILE), runs both and
// prints the ratio of the medians. Results: docs/performance.md.
//
//   build-h3/bench/comms/irgs_bench_decoder --benchmark_repetitions=5

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <span>
#include <string>
#include <vector>

#include "bench/comms/decoder_bench_stream.hpp"
#include "comms/mavlink/frame_decoder.hpp"
#include "comms/mavlink/messages.hpp"

namespace irgs::bench {
namespace {

namespace mav = comms::mavlink;

constexpr std::size_t kTicks = 2000;  // 100 s of telemetry
constexpr std::uint32_t kSeed = 3;

const std::vector<std::uint8_t>& stream() {
  static const std::vector<std::uint8_t> bytes = mixedTelemetryStream(kTicks, kSeed);
  return bytes;
}

std::size_t expectedFrames() {
  return kTicks * 11;
}

template <bool kUnpack>
void decode(benchmark::State& state) {
  const auto& bytes = stream();
  const auto chunk = static_cast<std::size_t>(state.range(0));
  mav::FrameDecoder decoder;
  std::vector<mav::Frame> frames;
  frames.reserve(256);
  std::size_t delivered = 0;
  double checksum = 0.0;  // keeps the unpacked values alive
  for (auto _ : state) {
    delivered = 0;
    for (std::size_t at = 0; at < bytes.size(); at += chunk) {
      const std::size_t n = std::min(chunk, bytes.size() - at);
      frames.clear();
      decoder.feed(std::span(bytes).subspan(at, n), frames);
      delivered += frames.size();
      if constexpr (kUnpack) {
        for (const mav::Frame& f : frames) {
          switch (f.message_id) {
            case mav::Heartbeat::kId:
              checksum += f.as<mav::Heartbeat>()->custom_mode;
              break;
            case mav::DistanceSensor::kId:
              checksum += f.as<mav::DistanceSensor>()->current_distance;
              break;
            case mav::Odometry::kId:
              checksum += static_cast<double>(f.as<mav::Odometry>()->x);
              break;
            case mav::ScaledImu::kId:
              checksum += f.as<mav::ScaledImu>()->zgyro;
              break;
            default:
              break;
          }
        }
      }
    }
    benchmark::DoNotOptimize(checksum);
  }
  if (delivered != expectedFrames()) {
    state.SkipWithError("decoder lost frames");
    return;
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * bytes.size()));
  state.counters["frames_per_s"] = benchmark::Counter(
      static_cast<double>(state.iterations() * delivered), benchmark::Counter::kIsRate);
  state.counters["stream_bytes"] = static_cast<double>(bytes.size());
}

void BM_FrameDecoder(benchmark::State& state) {
  decode<false>(state);
}
void BM_FrameDecoderUnpack(benchmark::State& state) {
  decode<true>(state);
}
BENCHMARK(BM_FrameDecoder)->Arg(64)->Arg(4096)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_FrameDecoderUnpack)->Arg(64)->Arg(4096)->Unit(benchmark::kMicrosecond);

// --write-stream FILE: writes the benchmark's stream (for the node-mavlink reference) and exits.
int writeStream(const char* path) {
  std::ofstream out(path, std::ios::binary);
  const auto& bytes = stream();
  out.write(reinterpret_cast<const char*>(bytes.data()),
            static_cast<std::streamsize>(bytes.size()));
  out.close();
  if (!out) {
    std::fprintf(stderr, "irgs_bench_decoder: cannot write %s\n", path);
    return 1;
  }
  std::printf("wrote %zu bytes, %zu frames (%zu ticks of 50 ms) to %s\n", bytes.size(),
              expectedFrames(), kTicks, path);
  return 0;
}

}  // namespace
}  // namespace irgs::bench

int main(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--write-stream") == 0) {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "irgs_bench_decoder: --write-stream needs a file\n");
        return 2;
      }
      return irgs::bench::writeStream(argv[i + 1]);
    }
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv))
    return 2;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
