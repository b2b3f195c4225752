// Simulator throughput in simulated seconds per wall second, for the indexed segment caster and
// the naive all-segments caster on the same scene, so their ratio shows in one run.
//
// Scene: a deterministic 500-wall map (a 30 m x 30 m room: 4 outer walls and 496 interior
// walls of 0.3-2.5 m, kept clear of the robot's path), the bundled thesis robot (8 sonars,
// 9 IR sensors, 6 bumpers) with its sonars at 20 Hz and 11 rays per cone, driving a 6 m
// diameter circle with the default noise model. Each iteration simulates 10 s. A third run
// uses the same walls drawn into a raster of the warehouse map's size (1006 x 1674 cells at
// 3 cm) instead of segments; BM_RasterWorldBuild times building that raster's world.
//
//   build-b/bench/sim/irgs_bench_sim --benchmark_repetitions=5
//
// The "x_realtime" counter is simulated seconds per wall second; the program ends by printing
// the ratio of the medians (indexed / naive). Results: docs/performance.md.

#include <benchmark/benchmark.h>

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <stdexcept>
#include <string>

#include "core/robot/robot_profile_file.hpp"
#include "core/sim/random.hpp"
#include "core/sim/simulator.hpp"

namespace irgs {
namespace {

constexpr double kLoopRadius_m = 3.0;
constexpr double kSpeed_mps = 0.3;
constexpr double kSimSecondsPerIteration = 10.0;

double distanceToCircle(const Vec2& p) {
  return std::abs(p.norm() - kLoopRadius_m);
}

// Closest distance from the loop circle to a segment, sampled densely (walls are short).
double segmentDistanceToLoop(const Vec2& a, const Vec2& b) {
  double d = 1e9;
  for (int i = 0; i <= 50; ++i)
    d = std::min(d, distanceToCircle(a + (b - a) * (i / 50.0)));
  return d;
}

WorldMap benchmarkWorld() {
  WorldMap world;
  world.name = "bench_500_walls";
  const double half = 15.0;
  auto addWall = [&](const Vec2& a, const Vec2& b) {
    Wall w;
    w.id = "w" + std::to_string(world.walls.size());
    w.points = {a, b};
    world.walls.push_back(std::move(w));
  };
  addWall({-half, -half}, {half, -half});
  addWall({half, -half}, {half, half});
  addWall({half, half}, {-half, half});
  addWall({-half, half}, {-half, -half});
  SimRandom rng(500);
  while (world.walls.size() < 500) {
    const Vec2 a(-half + 2 * half * rng.uniform(), -half + 2 * half * rng.uniform());
    const double length = 0.3 + 2.2 * rng.uniform();
    // Indoor-like: mostly axis-aligned, some slanted.
    const double angle =
        rng.uniform() < 0.7 ? (rng.uniform() < 0.5 ? 0.0 : kPi / 2) : kPi * rng.uniform();
    const Vec2 b = a + length * Vec2(std::cos(angle), std::sin(angle));
    if (std::abs(b.x()) > half || std::abs(b.y()) > half)
      continue;
    if (segmentDistanceToLoop(a, b) < 0.6)  // keep a 1.2 m corridor along the loop
      continue;
    addWall(a, b);
  }
  world.start = {kLoopRadius_m, 0.0, kPi / 2};  // on the circle, heading along it (CCW)
  return world;
}

// The same walls drawn into a raster of the warehouse map's size (1006 x 1674 cells at 3 cm,
// the largest bundled ROS map), unknown outside the room, free inside, walls occupied.
WorldMap benchmarkRasterWorld() {
  const WorldMap vector_world = benchmarkWorld();
  WorldMap world;
  world.name = "bench_500_walls_raster";
  world.start = vector_world.start;
  RasterLayer layer;
  layer.source = "generated";
  RasterMap& r = layer.raster;
  r.width = 1006;
  r.height = 1674;
  r.resolution_m = 0.03;
  r.origin = {-15.09, -25.11, 0.0};
  r.cells.assign(static_cast<std::size_t>(r.width) * static_cast<std::size_t>(r.height),
                 RasterMap::kUnknown);
  for (int row = 0; row < r.height; ++row) {
    for (int col = 0; col < r.width; ++col) {
      const Vec2 c = r.cellCentre(col, row);
      if (std::abs(c.x()) < 15.0 && std::abs(c.y()) < 15.0)
        r.at(col, row) = RasterMap::kFree;
    }
  }
  for (const Segment& s : vector_world.segments()) {
    const int samples = static_cast<int>(std::ceil(s.length() / (0.5 * r.resolution_m))) + 1;
    for (int i = 0; i <= samples; ++i) {
      if (const auto cell = r.worldToCell(s.a + (s.b - s.a) * (i / double(samples))))
        r.at(cell->first, cell->second) = RasterMap::kOccupied;
    }
  }
  world.raster = std::move(layer);
  return world;
}

RobotProfile benchmarkRobot() {
  const auto loaded =
      loadRobotProfileFile(std::string(IRGS_SOURCE_DIR) + "/resources/robots/thesis_robot.json");
  if (!loaded.ok())
    throw std::runtime_error("cannot load resources/robots/thesis_robot.json");
  RobotProfile robot = *loaded.profile;
  for (SonarSpec& s : robot.sonars)
    s.rate_hz = 20.0;
  return robot;
}

enum class Scene { kIndexedSegments, kNaiveSegments, kRaster };

void BM_SimulatorThroughput(benchmark::State& state, Scene scene) {
  SimConfig config;  // default noise: dropouts, range noise, 11 rays per cone
  config.sonar.rays_per_cone = 11;
  config.segment_caster =
      scene == Scene::kNaiveSegments ? SegmentCasterKind::kNaive : SegmentCasterKind::kIndexed;
  config.odometry.slip_stddev = 0.002;
  Simulator sim(scene == Scene::kRaster ? benchmarkRasterWorld() : benchmarkWorld(),
                benchmarkRobot(), config);
  sim.setCommand({kSpeed_mps, kSpeed_mps / kLoopRadius_m});
  const auto steps = static_cast<int>(std::lround(kSimSecondsPerIteration / config.dt_s));
  TelemetrySample sample;
  std::int64_t readings = 0;
  for (auto _ : state) {
    for (int i = 0; i < steps; ++i) {
      sim.step(sample);
      readings += static_cast<std::int64_t>(sample.sonar.size());
    }
    benchmark::DoNotOptimize(sample);
  }
  state.counters["x_realtime"] =
      benchmark::Counter(kSimSecondsPerIteration * static_cast<double>(state.iterations()),
                         benchmark::Counter::kIsRate);
  state.counters["sonar_readings"] =
      benchmark::Counter(static_cast<double>(readings), benchmark::Counter::kAvgIterations);
  // The robot must really be driving its loop, not stuck against a wall.
  if (sim.bumpers() != 0 || distanceToCircle(sim.truePose().position()) > 0.5)
    state.SkipWithError("the robot left its loop");
}

BENCHMARK_CAPTURE(BM_SimulatorThroughput, indexed, Scene::kIndexedSegments)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_SimulatorThroughput, naive, Scene::kNaiveSegments)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_SimulatorThroughput, raster_warehouse_size, Scene::kRaster)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// Building the simulator's view of a warehouse-sized raster (solidity + distance transform):
// what a map switch or an edit costs.
void BM_RasterWorldBuild(benchmark::State& state) {
  const WorldMap world = benchmarkRasterWorld();
  for (auto _ : state) {
    SimWorld sim_world(world, {});
    benchmark::DoNotOptimize(&sim_world);
  }
}
BENCHMARK(BM_RasterWorldBuild)->Unit(benchmark::kMillisecond)->UseRealTime();

// Prints the usual console table, then the indexed/naive ratio of the medians (or of the
// single runs when not repeating).
class RatioReporter : public benchmark::ConsoleReporter {
 public:
  RatioReporter() : ConsoleReporter(isatty(fileno(stdout)) ? OO_Defaults : OO_Tabular) {}

  void ReportRuns(const std::vector<Run>& runs) override {
    ConsoleReporter::ReportRuns(runs);
    for (const Run& run : runs) {
      const std::string name = run.benchmark_name();
      const bool median = run.aggregate_name == "median";
      const bool single = run.run_type == Run::RT_Iteration;
      const auto it = run.counters.find("x_realtime");
      if (it == run.counters.end() || !(median || single))
        continue;
      if (name.find("indexed") == std::string::npos && name.find("naive") == std::string::npos)
        continue;
      const std::string kind = name.find("indexed") != std::string::npos ? "indexed" : "naive";
      if (median || !have_median_[kind])
        rate_[kind] = it->second.value;
      have_median_[kind] = have_median_[kind] || median;
    }
  }
  void Finalize() override {
    ConsoleReporter::Finalize();
    if (rate_.count("indexed") && rate_.count("naive") && rate_["naive"] > 0.0) {
      std::printf("\nsimulated s per wall s: indexed %.0f, naive %.0f; indexed/naive = %.1fx\n",
                  rate_["indexed"], rate_["naive"], rate_["indexed"] / rate_["naive"]);
    }
  }

 private:
  std::map<std::string, double> rate_;
  std::map<std::string, bool> have_median_;
};

}  // namespace
}  // namespace irgs

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv))
    return 1;
  irgs::RatioReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::Shutdown();
  return 0;
}
