// Cone updates per second of OccupancyGrid::integrateSonar (scanline rasteriser) beside
// integrateSonarNaive (every cell of the bounding box with atan2/hypot), same cones, same run.
// Typical sonar cones: 25 degree beam, echo at 0.5, 1.5 or 3 m, random poses in a 10 m x 10 m
// room, 1 cm cells. Also the simulator workload (10,000 cones, 0.5..4 m) and whole-grid reads.

#include <benchmark/benchmark.h>

#include <algorithm>
#include <random>
#include <vector>

#include "core/mapping/occupancy_grid.hpp"
#include "core/mapping/sonar_cone.hpp"

namespace irgs {
namespace {

constexpr double kResolution = 0.01;
const double kBeam = degToRad(25.0);

struct Shot {
  Vec2 origin;
  double heading_rad;
  double range_m;
  bool echo;
};

std::vector<Shot> randomShots(std::size_t n, double min_range_m, double max_range_m,
                              double echo_fraction, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Shot> shots(n);
  for (Shot& s : shots) {
    s.origin = Vec2(10.0 * unit(rng), 10.0 * unit(rng));
    s.heading_rad = wrapAngle(2.0 * kPi * unit(rng));
    s.range_m = min_range_m + (max_range_m - min_range_m) * unit(rng);
    s.echo = unit(rng) < echo_fraction;
  }
  return shots;
}

template <bool kFast>
void coneUpdates(benchmark::State& state) {
  const double range_m = static_cast<double>(state.range(0)) / 100.0;
  const std::vector<Shot> shots = randomShots(4096, range_m, range_m, 1.0, 42);
  const SonarInverseModel model;
  OccupancyGrid grid(kResolution);
  // Warm up: allocate the room's tiles so that growth is not what is measured.
  for (const Shot& s : shots)
    grid.integrateSonar(s.origin, s.heading_rad, kBeam, s.range_m, s.echo, model);
  const std::uint64_t cells_before = grid.cellUpdates();
  std::size_t i = 0;
  for (auto _ : state) {
    const Shot& s = shots[i++ % shots.size()];
    if constexpr (kFast)
      grid.integrateSonar(s.origin, s.heading_rad, kBeam, s.range_m, s.echo, model);
    else
      grid.integrateSonarNaive(s.origin, s.heading_rad, kBeam, s.range_m, s.echo, model);
  }
  benchmark::DoNotOptimize(grid.observedCellCount());
  state.counters["cones/s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["cells/s"] = benchmark::Counter(
      static_cast<double>(grid.cellUpdates() - cells_before), benchmark::Counter::kIsRate);
}

void BM_ConeFast(benchmark::State& state) {
  coneUpdates<true>(state);
}
void BM_ConeNaive(benchmark::State& state) {
  coneUpdates<false>(state);
}
// Argument: echo range in centimetres.
BENCHMARK(BM_ConeFast)->Arg(50)->Arg(150)->Arg(300)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ConeNaive)->Arg(50)->Arg(150)->Arg(300)->Unit(benchmark::kMicrosecond);

// The row scan alone (sonar_cone.cpp: the geometry, no grid writes), to split a cone update's
// time between finding the cells and updating them. Same cones as BM_ConeFast.
void BM_ConeRowScanOnly(benchmark::State& state) {
  const double range_m = static_cast<double>(state.range(0)) / 100.0;
  const std::vector<Shot> shots = randomShots(4096, range_m, range_m, 1.0, 42);
  const SonarInverseModel model;
  std::vector<SonarCone> cones;
  for (const Shot& s : shots)
    cones.push_back(makeSonarCone(s.origin, s.heading_rad, kBeam, s.range_m, s.echo, model));
  std::vector<ConeRow> rows;
  std::size_t i = 0, total_rows = 0;
  for (auto _ : state) {
    scanConeRows(cones[i++ % cones.size()], kResolution, rows);
    total_rows += rows.size();
    benchmark::DoNotOptimize(rows.data());
  }
  state.counters["rows/cone"] =
      static_cast<double>(total_rows) /
      static_cast<double>(std::max<benchmark::IterationCount>(state.iterations(), 1));
}
BENCHMARK(BM_ConeRowScanOnly)->Arg(50)->Arg(150)->Arg(300)->Unit(benchmark::kMicrosecond);

// The simulator's budget: a 120 s drive with 8 sonars at 10 Hz is ~10,000 cones with ranges
// mostly 0.5..4 m (some without echo), into a fresh grid (growth included).
void BM_SimDriveWorkload10kCones(benchmark::State& state) {
  const std::vector<Shot> shots = randomShots(10000, 0.5, 4.0, 0.8, 7);
  const SonarInverseModel model;
  std::uint64_t cells = 0;
  for (auto _ : state) {
    OccupancyGrid grid(kResolution);
    for (const Shot& s : shots)
      grid.integrateSonar(s.origin, s.heading_rad, kBeam, s.range_m, s.echo, model);
    cells += grid.cellUpdates();
    benchmark::DoNotOptimize(grid.observedCellCount());
  }
  state.counters["cells/s"] =
      benchmark::Counter(static_cast<double>(cells), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_SimDriveWorkload10kCones)->Unit(benchmark::kMillisecond);

// A GUI frame reading the whole grid: a 20 m x 20 m explored area at 1 cm (4 M cells).
OccupancyGrid exploredRoom() {
  OccupancyGrid grid(kResolution);
  const SonarInverseModel model;
  for (const Shot& s : randomShots(20000, 0.5, 4.0, 0.8, 9))
    grid.integrateSonar(2.0 * s.origin, s.heading_rad, kBeam, s.range_m, s.echo, model);
  return grid;
}

void BM_WholeGridCopyLogOdds(benchmark::State& state) {
  const OccupancyGrid grid = exploredRoom();
  const OccupancyGrid::CellRect rect = grid.observedCellRect();
  std::vector<float> values;
  for (auto _ : state) {
    grid.copyLogOdds(rect, values);
    benchmark::DoNotOptimize(values.data());
  }
  state.counters["cells"] = static_cast<double>(values.size());
  state.counters["cells/s"] = benchmark::Counter(
      static_cast<double>(values.size()) * static_cast<double>(state.iterations()),
      benchmark::Counter::kIsRate);
}
BENCHMARK(BM_WholeGridCopyLogOdds)->Unit(benchmark::kMillisecond);

void BM_WholeGridToRaster(benchmark::State& state) {
  const OccupancyGrid grid = exploredRoom();
  for (auto _ : state) {
    RasterMap raster = grid.toRaster();
    benchmark::DoNotOptimize(raster.cells.data());
  }
}
BENCHMARK(BM_WholeGridToRaster)->Unit(benchmark::kMillisecond);

void BM_GridCopy(benchmark::State& state) {
  const OccupancyGrid grid = exploredRoom();
  for (auto _ : state) {
    OccupancyGrid copy = grid;
    benchmark::DoNotOptimize(copy.tileCount());
  }
  state.counters["MB"] = static_cast<double>(grid.memoryBytes()) / 1e6;
}
BENCHMARK(BM_GridCopy)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace irgs

BENCHMARK_MAIN();
