// Sonar insertion into a 1 cm occupancy grid: IRGS's OccupancyGrid::integrateSonar beside MRPT's
// COccupancyGridMap2D::insertObservation with a CObservationRange holding the same reading, same
// run, same cones (issue 4 acceptance: ours at least as fast). 30 degree cone, echo at 0.5, 1.5
// or 3 m, 4096 random poses in a 10 m x 10 m room. Both grids are warmed up first: ours has its
// room tiles allocated, MRPT's grid is allocated over every cone (-4..14 m) from the start.
//
// What each side computes per reading (docs/performance.md has the figures):
// - IRGS: the exact circular sector (cell centres inside the beam's two half-planes; free below
//   range - arc/2, occupied on the 3 cm arc band), log-odds +0.85 / -0.4 clamped to [-4, 4] on
//   16-bit cells (steps of 1/4096), plus the newly-observed count and the dirty rectangle. With
//   the widest instruction set the CPU has (BM_IrgsSonarInsert30deg) and, where AVX-512 is that,
//   with AVX2 too (BM_IrgsAvx2SonarInsert30deg: what an AVX2-only machine runs) and with the
//   portable path (BM_IrgsPortableSonarInsert30deg: SSE2, what any x86-64 runs).
// - MRPT: its own sonar model on 8-bit cells (a triangle apex / edge end points filled free, the
//   cells near the range marked occupied), after composing the robot and sensor poses.
// Built only when libmrpt-dev is installed (bench/mapping/CMakeLists.txt).

#include <benchmark/benchmark.h>

#include <mrpt/maps/COccupancyGridMap2D.h>
#include <mrpt/obs/CObservationRange.h>
#include <mrpt/poses/CPose3D.h>

#include <random>
#include <stdexcept>
#include <vector>

#include "core/mapping/occupancy_grid.hpp"

namespace irgs {
namespace {

constexpr double kResolution = 0.01;
const double kBeam = degToRad(30.0);

struct Shot {
  Vec2 origin;
  double heading_rad;
  double range_m;
};

std::vector<Shot> randomShots(std::size_t n, double range_m, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Shot> shots(n);
  for (Shot& s : shots) {
    s.origin = Vec2(10.0 * unit(rng), 10.0 * unit(rng));
    s.heading_rad = wrapAngle(2.0 * kPi * unit(rng));
    s.range_m = range_m;
  }
  return shots;
}

// The reading as MRPT takes it: one measurement, the sensor pose in the robot frame, the robot
// at the origin.
std::vector<mrpt::obs::CObservationRange> mrptObservations(const std::vector<Shot>& shots) {
  std::vector<mrpt::obs::CObservationRange> out(shots.size());
  for (std::size_t i = 0; i < shots.size(); ++i) {
    mrpt::obs::CObservationRange& obs = out[i];
    obs.minSensorDistance = 0.0f;
    obs.maxSensorDistance = 5.0f;
    obs.sensorConeApperture = static_cast<float>(kBeam);
    mrpt::obs::CObservationRange::TMeasurement m;
    m.sensorID = 0;
    m.sensorPose = mrpt::math::TPose3D(shots[i].origin.x(), shots[i].origin.y(), 0.0,
                                       shots[i].heading_rad, 0.0, 0.0);
    m.sensedDistance = static_cast<float>(shots[i].range_m);
    obs.sensedData.push_back(m);
  }
  return out;
}

void irgsSonarInsert(benchmark::State& state, GridSimd simd) {
  const std::vector<Shot> shots =
      randomShots(4096, static_cast<double>(state.range(0)) / 100.0, 42);
  const SonarInverseModel model;
  OccupancyGrid grid(kResolution);
  grid.setSimd(simd);
  for (const Shot& s : shots)
    grid.integrateSonar(s.origin, s.heading_rad, kBeam, s.range_m, true, model);
  const std::uint64_t before = grid.cellUpdates();
  std::size_t i = 0;
  for (auto _ : state) {
    const Shot& s = shots[i++ % shots.size()];
    grid.integrateSonar(s.origin, s.heading_rad, kBeam, s.range_m, true, model);
  }
  benchmark::DoNotOptimize(grid.observedCellCount());
  state.counters["cones/s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["cells/cone"] =
      static_cast<double>(grid.cellUpdates() - before) /
      static_cast<double>(std::max<benchmark::IterationCount>(state.iterations(), 1));
}

void BM_IrgsSonarInsert30deg(benchmark::State& state) {
  irgsSonarInsert(state, bestGridSimd());
}

void BM_IrgsAvx2SonarInsert30deg(benchmark::State& state) {
  if (!gridSimdSupported(GridSimd::kAvx2) || bestGridSimd() == GridSimd::kAvx2) {
    state.SkipWithError("AVX2 not supported or already the default (BM_IrgsSonarInsert30deg)");
    return;
  }
  irgsSonarInsert(state, GridSimd::kAvx2);
}

void BM_IrgsPortableSonarInsert30deg(benchmark::State& state) {
  if (bestGridSimd() == GridSimd::kPortable) {
    state.SkipWithError("the portable path is already the default (BM_IrgsSonarInsert30deg)");
    return;
  }
  irgsSonarInsert(state, GridSimd::kPortable);
}

void BM_MrptSonarInsert30deg(benchmark::State& state) {
  const std::vector<Shot> shots =
      randomShots(4096, static_cast<double>(state.range(0)) / 100.0, 42);
  const std::vector<mrpt::obs::CObservationRange> observations = mrptObservations(shots);
  // Preallocated to hold every cone: MRPT grows its grid from the boresight end point only, so
  // a cone whose edge leaves the grid writes out of bounds (seen as a crash at 3 m).
  mrpt::maps::COccupancyGridMap2D grid(-4.0f, 14.0f, -4.0f, 14.0f, static_cast<float>(kResolution));
  for (const auto& obs : observations)
    grid.insertObservation(obs);
  // The insertion must have changed cells, or the comparison is void.
  std::size_t changed = 0;
  for (unsigned y = 0; y < grid.getSizeY(); ++y)
    for (unsigned x = 0; x < grid.getSizeX(); ++x)
      changed += grid.getCell(static_cast<int>(x), static_cast<int>(y)) != 0.5f ? 1 : 0;
  if (changed == 0)
    throw std::runtime_error("MRPT grid unchanged by the sonar observations");
  state.counters["changed_cells"] = static_cast<double>(changed);
  std::size_t i = 0;
  for (auto _ : state) {
    const bool inserted = grid.insertObservation(observations[i++ % observations.size()]);
    benchmark::DoNotOptimize(inserted);
  }
  state.counters["cones/s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

// Argument: echo range in centimetres.
BENCHMARK(BM_IrgsSonarInsert30deg)->Arg(50)->Arg(150)->Arg(300)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_IrgsAvx2SonarInsert30deg)->Arg(50)->Arg(150)->Arg(300)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_IrgsPortableSonarInsert30deg)
    ->Arg(50)
    ->Arg(150)
    ->Arg(300)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_MrptSonarInsert30deg)->Arg(50)->Arg(150)->Arg(300)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace irgs

BENCHMARK_MAIN();
