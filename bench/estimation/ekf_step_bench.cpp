// One EKF step of the paper-000 localizer (differential-drive predict + one stereo-sonar update:
// inversion (5)-(8), matching (38)-(43) over the map, sequential d and theta updates in Joseph
// form) beside a bare fixed-size Eigen reference doing the same arithmetic without the
// diagnostics, in the same run. Requirement (issue 5): EkfLocalizer <= 2x the reference, and no
// heap allocation per step — counted by the replaced global operator new below.
//
//   build-h8/bench/estimation/irgs_bench_estimation --benchmark_repetitions=9 (and
//       --benchmark_report_aggregates_only=true for the medians only)
//
// Two maps: the bundled paper-000 corridor (resources/maps/corridor_000_table1.json, both faces
// of every wall piece, so the matching loop visits every face) and a two-wall map where the
// matching is negligible and the step is almost pure filter numerics. The reference matches
// over the same faces with the same rules. The program ends by printing the ratio of the
// medians and the heap allocations per step.

#include <benchmark/benchmark.h>

#include <array>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <map>
#include <new>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "core/estimation/ekf_localizer.hpp"
#include "core/estimation/stereo_echo_sim.hpp"
#include "core/estimation/stereo_measurement_model.hpp"
#include "core/world/map_file.hpp"

// ---- allocation counting: every operator new of the process goes through here ----
// new = malloc and delete = free are a matching pair; GCC cannot see that across the
// replacement functions and warns (-Wmismatched-new-delete) where it inlines them.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
#endif
namespace {
std::atomic<long long> g_allocations{0};
}  // namespace

void* operator new(std::size_t size) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(size == 0 ? 1 : size))
    return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t size) {
  return operator new(size);
}
void operator delete(void* p) noexcept {
  std::free(p);
}
void operator delete[](void* p) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
  std::free(p);
}
void operator delete[](void* p, std::size_t) noexcept {
  std::free(p);
}

namespace irgs {
namespace {

constexpr double kWheelbase = 0.4;
constexpr double kHalfBaseline = 0.2;
const SensorMount kRight{0.0, -0.2, -kPi / 2};

struct Scenario {
  LocalizationMap map;
  LocState x0;
  LocCov p0;
  std::vector<EchoPaths> readings;  // noisy echoes of the wall on the right, from x0
};

Scenario makeScenario(const WorldMap& world, const Pose2& pose) {
  Scenario s;
  s.map = buildLocalizationMap(world);
  s.x0 = toLocState(pose);
  s.p0 = LocCov::Zero();
  s.p0.diagonal() << 0.02 * 0.02, 0.02 * 0.02, degToRad(2.0) * degToRad(2.0);
  const StereoEchoSimulator sim(world, {}, {});
  SimRandom rng(5);
  for (int i = 0; i < 64; ++i) {
    const SimulatedEcho e = sim.echo(sensorWorldPose(s.x0, kRight), rng);
    if (e.status != EchoStatus::kEcho)
      throw std::runtime_error("bench scenario: the right sensor sees no wall");
    s.readings.push_back(e.paths);
  }
  return s;
}

const Scenario& corridor() {
  static const Scenario s = [] {
    const MapLoadResult loaded =
        loadMapFile(std::string(IRGS_SOURCE_DIR) + "/resources/maps/corridor_000_table1.json");
    if (!loaded.map)
      throw std::runtime_error("cannot load resources/maps/corridor_000_table1.json");
    return makeScenario(*loaded.map, {5.0, 0.775, 0.0});
  }();
  return s;
}

const Scenario& twoWalls() {
  static const Scenario s = [] {
    WorldMap world;
    world.walls.push_back({"long", {{-5.0, -1.0}, {40.0, -1.0}}, false, {}});
    world.walls.push_back({"cross", {{21.0, -1.0}, {21.0, 3.0}}, false, {}});
    return makeScenario(world, {5.0, 0.0, 0.0});
  }();
  return s;
}

// Alternating forward/backward wheel travel keeps the state near x0 over millions of steps.
inline double travel(long i) {
  return (i & 1) != 0 ? -0.003 : 0.003;
}

// ---------------- the bare reference: same arithmetic, plain fixed-size Eigen ----------------
struct Face {
  double phi = 0.0;  // robot-facing normal angle
  double p = 0.0;    // robot-facing distance
};
struct Point {
  double x = 0.0, y = 0.0;
};

struct BareEkf {
  Eigen::Vector3d x;
  Eigen::Matrix3d p;
  std::vector<Face> faces;
  std::vector<Point> points;

  void predict(double l, double r) {
    const double ds = 0.5 * (l + r), dphi = (r - l) / kWheelbase;
    const double a = x(2) + 0.5 * dphi, ca = std::cos(a), sa = std::sin(a);
    x(0) += ds * ca;
    x(1) += ds * sa;
    x(2) = wrapAngle(x(2) + dphi);
    Eigen::Matrix3d f = Eigen::Matrix3d::Identity();
    f(0, 2) = -ds * sa;
    f(1, 2) = ds * ca;
    Eigen::Matrix<double, 3, 2> g;
    const double k = ds / (2.0 * kWheelbase);
    g << 0.5 * ca + k * sa, 0.5 * ca - k * sa, 0.5 * sa - k * ca, 0.5 * sa + k * ca,
        -1.0 / kWheelbase, 1.0 / kWheelbase;
    const Eigen::Vector2d q(1e-4 * std::abs(l), 1e-4 * std::abs(r));
    p = f * p * f.transpose() + g * q.asDiagonal() * g.transpose();
    p = 0.5 * (p + p.transpose());
  }

  void scalar(double v, const Eigen::RowVector3d& h, double rvar) {
    const Eigen::Vector3d ph = p * h.transpose();
    const double s = h.dot(ph) + rvar;
    const Eigen::Vector3d w = ph / s;
    x += w * v;
    x(2) = wrapAngle(x(2));
    const Eigen::Matrix3d ikh = Eigen::Matrix3d::Identity() - w * h;
    p = ikh * p * ikh.transpose() + (w * rvar) * w.transpose();
    p = 0.5 * (p + p.transpose());
  }

  void update(const EchoPaths& e, const SensorMount& m) {
    const double s2 = kHalfBaseline * kHalfBaseline;
    const double rad = 0.5 * (e.r1_m * e.r1_m + e.r2_m * e.r2_m) - s2;
    if (!(rad > 0.0))
      return;
    const double d = 0.5 * std::sqrt(rad);
    const double sn = (e.r1_m * e.r1_m - e.r2_m * e.r2_m) / (8.0 * kHalfBaseline * d);
    if (!(std::abs(sn) < 1.0))
      return;
    const double theta = std::asin(sn);
    const double c = std::cos(x(2)), sphi = std::sin(x(2));
    const double xt = x(0) + m.x_m * c - m.y_m * sphi, yt = x(1) + m.x_m * sphi + m.y_m * c;
    const double phit = wrapAngle(x(2) + m.phi_rad + theta);
    const double tx = xt + d * std::cos(phit), ty = yt + d * std::sin(phit);
    for (const Point& pt : points) {
      if (std::hypot(pt.x - tx, pt.y - ty) <= 0.1)
        return;  // the scenarios have no point within eps1; only the search is timed
    }
    int best = -1;
    double best_m2 = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < faces.size(); ++i) {
      if (!(std::abs(wrapAngle(phit - faces[i].phi)) <= degToRad(10.0)))
        continue;
      const double dh = faces[i].p - xt * std::cos(faces[i].phi) - yt * std::sin(faces[i].phi);
      if (!(dh > 0.0))
        continue;
      if (std::abs(dh - d) < best_m2) {
        best_m2 = std::abs(dh - d);
        best = static_cast<int>(i);
      }
    }
    if (best < 0)
      return;
    const Face& f = faces[static_cast<std::size_t>(best)];
    const double dh = f.p - xt * std::cos(f.phi) - yt * std::sin(f.phi);
    const Eigen::RowVector3d hd(-std::cos(f.phi), -std::sin(f.phi),
                                m.x_m * std::sin(x(2) - f.phi) + m.y_m * std::cos(x(2) - f.phi));
    scalar(d - dh, hd, 0.01 * 0.01);
    const double th = wrapAngle(f.phi - x(2) - m.phi_rad);
    scalar(wrapAngle(theta - th), Eigen::RowVector3d(0.0, 0.0, -1.0),
           degToRad(2.0) * degToRad(2.0));
  }
};

BareEkf makeBare(const Scenario& s) {
  BareEkf b;
  b.x = s.x0;
  b.p = s.p0;
  for (const MapWallFace& w : s.map.walls)
    b.faces.push_back({w.facing.phi_eff_rad, w.facing.p_eff_m});
  for (const MapPoint& pt : s.map.points)
    b.points.push_back({pt.position.x(), pt.position.y()});
  return b;
}

// ---------------- the benchmarks ----------------
long long allocationsPerThousandSteps(const Scenario& s) {
  EkfLocalizer ekf(s.x0, s.p0);
  const DiffDriveNoise noise{1e-4, LocCov::Zero()};
  const long long before = g_allocations.load();
  for (long i = 0; i < 1000; ++i) {
    ekf.predictDiffDrive(travel(i), travel(i), kWheelbase, noise);
    benchmark::DoNotOptimize(ekf.update(s.readings[static_cast<std::size_t>(i) % s.readings.size()],
                                        {kRight, kHalfBaseline}, s.map));
  }
  return g_allocations.load() - before;
}

void runEkf(benchmark::State& state, const Scenario& s) {
  EkfLocalizer ekf(s.x0, s.p0);
  const DiffDriveNoise noise{1e-4, LocCov::Zero()};
  long i = 0;
  int updated = 0;
  const long long before = g_allocations.load();
  for (auto _ : state) {
    ekf.predictDiffDrive(travel(i), travel(i), kWheelbase, noise);
    const LocalizationUpdate u =
        ekf.update(s.readings[static_cast<std::size_t>(i) % s.readings.size()],
                   {kRight, kHalfBaseline}, s.map);
    updated += u.status == UpdateStatus::kUpdated ? 1 : 0;
    benchmark::DoNotOptimize(u);
    ++i;
  }
  const long long allocs = g_allocations.load() - before;
  if (updated < i - 1)
    state.SkipWithError("some steps did not update: the scenario is broken");
  state.counters["allocs_per_step"] = static_cast<double>(allocs) / static_cast<double>(i);
  state.counters["faces"] = static_cast<double>(s.map.walls.size());
}

void runBare(benchmark::State& state, const Scenario& s) {
  BareEkf b = makeBare(s);
  long i = 0;
  for (auto _ : state) {
    b.predict(travel(i), travel(i));
    b.update(s.readings[static_cast<std::size_t>(i) % s.readings.size()], kRight);
    benchmark::DoNotOptimize(b.x);
    benchmark::DoNotOptimize(b.p);
    ++i;
  }
  state.counters["faces"] = static_cast<double>(b.faces.size());
}

void BM_EkfStepCorridor(benchmark::State& state) {
  runEkf(state, corridor());
}
void BM_BareEigenStepCorridor(benchmark::State& state) {
  runBare(state, corridor());
}
void BM_EkfStepTwoWalls(benchmark::State& state) {
  runEkf(state, twoWalls());
}
void BM_BareEigenStepTwoWalls(benchmark::State& state) {
  runBare(state, twoWalls());
}
BENCHMARK(BM_EkfStepCorridor);
BENCHMARK(BM_BareEigenStepCorridor);
BENCHMARK(BM_EkfStepTwoWalls);
BENCHMARK(BM_BareEigenStepTwoWalls);

// Collects the medians (or the single runs) to print the ratios at the end, of wall time and of
// CPU time (the latter is the fairer figure on a loaded machine).
class RatioReporter : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    ConsoleReporter::ReportRuns(runs);
    for (const Run& r : runs) {
      if (r.run_type == Run::RT_Aggregate && r.aggregate_name != "median")
        continue;
      times_[r.run_name.function_name] = {r.GetAdjustedRealTime(), r.GetAdjustedCPUTime()};
    }
  }
  void print() const {
    auto ratio = [&](const char* a, const char* b) {
      const auto ia = times_.find(a), ib = times_.find(b);
      if (ia == times_.end() || ib == times_.end() || !(ib->second.first > 0.0) ||
          !(ib->second.second > 0.0))
        return;
      std::printf("%s / %s = %.2f wall time, %.2f CPU time (requirement <= 2)\n", a, b,
                  ia->second.first / ib->second.first, ia->second.second / ib->second.second);
    };
    ratio("BM_EkfStepCorridor", "BM_BareEigenStepCorridor");
    ratio("BM_EkfStepTwoWalls", "BM_BareEigenStepTwoWalls");
  }

 private:
  std::map<std::string, std::pair<double, double>> times_;  // wall, CPU
};

}  // namespace
}  // namespace irgs

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv))
    return 1;
  irgs::RatioReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  reporter.print();
  std::printf("heap allocations per 1000 EkfLocalizer steps: corridor %lld, two walls %lld\n",
              irgs::allocationsPerThousandSteps(irgs::corridor()),
              irgs::allocationsPerThousandSteps(irgs::twoWalls()));
  benchmark::Shutdown();
  return 0;
}
