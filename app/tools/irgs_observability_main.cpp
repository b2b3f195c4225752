// irgs-observability: paper 001_… in the terminal (docs/dead-reckoning.md).
//   default            rank and null space of the total observability matrix (TOM) of the 9-,
//                      8- and 7-state dead-reckoning error models, for physically consistent
//                      segments (gyro increment = encoder rotation) and for independent ones
//   --loop-experiment  the 120 m / 4-waypoint loop over N seeds: per-seed final errors of the
//                      feedback filter and of raw encoder DR, medians; optional CSV outputs
//   --calibrate        the simulated rate-table + temperature-cycled calibration, fitted vs true
//   values
// Exit codes: 0 success, 1 runtime failure (file not writable), 2 usage error.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <fstream>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "core/estimation/dr_experiment.hpp"
#include "core/estimation/observability.hpp"
#include "core/sim/gyro_sim.hpp"

namespace {

using namespace irgs;

constexpr const char* kUsage =
    "usage: irgs-observability [--segments N] [--seed S] [--wheelbase M]\n"
    "                          [--kind consistent|independent|both]\n"
    "       irgs-observability --loop-experiment [--seeds N] [--first-seed S]\n"
    "                          [--gyro-scale-stddev X] [--csv FILE] [--trace-csv FILE]\n"
    "       irgs-observability --calibrate [--seed S]\n";

struct Options {
  enum class Mode { kObservability, kLoop, kCalibrate } mode = Mode::kObservability;
  int segments = 12;
  std::uint64_t seed = 1;
  double wheelbase_m = 0.5;
  std::string kind = "both";
  int seeds = 20;
  std::optional<double> gyro_scale_stddev;
  std::string csv;
  std::string trace_csv;
};

struct UsageError {
  std::string message;
};

double number(const std::string& option, const std::string& text) {
  try {
    std::size_t used = 0;
    const double v = std::stod(text, &used);
    if (used == text.size() && std::isfinite(v))
      return v;
  } catch (const std::exception&) {
  }
  throw UsageError{option + ": not a number: '" + text + "'"};
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const auto value = [&]() -> std::string {
      if (i + 1 >= argc)
        throw UsageError{a + " needs a value"};
      return argv[++i];
    };
    if (a == "--loop-experiment") {
      o.mode = Options::Mode::kLoop;
    } else if (a == "--calibrate") {
      o.mode = Options::Mode::kCalibrate;
    } else if (a == "--segments") {
      const double v = number(a, value());
      if (v < 1 || v > 1000 || v != static_cast<int>(v))
        throw UsageError{"--segments must be an integer in [1, 1000]"};
      o.segments = static_cast<int>(v);
    } else if (a == "--seed" || a == "--first-seed") {
      const double v = number(a, value());
      if (v < 0 || v > 1e15 || v != static_cast<double>(static_cast<std::uint64_t>(v)))
        throw UsageError{a + " must be a non-negative integer"};
      o.seed = static_cast<std::uint64_t>(v);
    } else if (a == "--seeds") {
      const double v = number(a, value());
      if (v < 1 || v > 10000 || v != static_cast<int>(v))
        throw UsageError{"--seeds must be an integer in [1, 10000]"};
      o.seeds = static_cast<int>(v);
    } else if (a == "--wheelbase") {
      o.wheelbase_m = number(a, value());
      if (!(o.wheelbase_m > 0.0))
        throw UsageError{"--wheelbase must be > 0"};
    } else if (a == "--kind") {
      o.kind = value();
      if (o.kind != "consistent" && o.kind != "independent" && o.kind != "both")
        throw UsageError{"--kind must be consistent, independent or both"};
    } else if (a == "--gyro-scale-stddev") {
      o.gyro_scale_stddev = number(a, value());
      if (*o.gyro_scale_stddev < 0.0 || *o.gyro_scale_stddev >= 0.5)
        throw UsageError{"--gyro-scale-stddev must be in [0, 0.5)"};
    } else if (a == "--csv") {
      o.csv = value();
    } else if (a == "--trace-csv") {
      o.trace_csv = value();
    } else if (a == "--help" || a == "-h") {
      std::cout << kUsage;
      std::exit(0);
    } else {
      throw UsageError{"unknown option '" + a + "'"};
    }
  }
  return o;
}

int observability(const Options& o) {
  const char* names[] = {"9-state (9)/(10)", "8-state (15)/(16)", "7-state (17)/(18)"};
  const DrModelKind kinds[] = {DrModelKind::kNineState, DrModelKind::kEightState,
                               DrModelKind::kSevenState};
  for (SegmentKind kind : {SegmentKind::kConsistent, SegmentKind::kIndependent}) {
    const bool consistent = kind == SegmentKind::kConsistent;
    if (o.kind != "both" && (o.kind == "consistent") != consistent)
      continue;
    std::cout << "== " << o.segments << " random piecewise-constant segments, seed " << o.seed
              << ", D = " << o.wheelbase_m << " m, gyro increment "
              << (consistent ? "= (R - L) / D (physically consistent)"
                             : "independent of R, L (digest's check)")
              << " ==\n";
    const auto segments = randomSegments(o.segments, o.seed, kind, o.wheelbase_m);
    for (int m = 0; m < 3; ++m) {
      std::cout << names[m] << ": "
                << formatReport(kinds[m], analyseObservability(kinds[m], segments));
    }
    std::cout << "\n";
  }
  std::cout << "001_… reports rank 6 for all three models; the structural null direction\n"
               "(S_R, S_L, dD) ~ (1, 1, D) caps the rank at 5 (docs/dead-reckoning.md).\n";
  return 0;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

int loop(const Options& o) {
  std::ofstream csv, trace;
  if (!o.csv.empty()) {
    csv.open(o.csv);
    if (!csv) {
      std::cerr << "irgs-observability: cannot write " << o.csv << "\n";
      return 1;
    }
    csv << "seed,completed,duration_s,distance_m,return_to_start_m,filtered_error_m,"
           "encoder_dr_error_m,filtered_heading_error_deg,encoder_dr_heading_error_deg,"
           "true_S_R,true_S_L,true_dD_m,est_right_scale,est_left_scale,est_wheelbase_m,"
           "est_gyro_scale,est_gyro_bias_dph,mode,updates,gated,mean_nis\n";
  }
  if (!o.trace_csv.empty()) {
    trace.open(o.trace_csv);
    if (!trace) {
      std::cerr << "irgs-observability: cannot write " << o.trace_csv << "\n";
      return 1;
    }
    trace << "seed,time_s,true_x,true_y,true_theta,filtered_x,filtered_y,filtered_theta,"
             "encoder_x,encoder_y,encoder_theta,sd_dx,sd_dy,sd_dpsi,sd_S_R,sd_S_L,sd_dD,sd_dphi,"
             "sd_dB_s,sd_dB_rb\n";
  }
  GyroErrorModel gyro = autogyroErrorModel();
  if (o.gyro_scale_stddev)
    gyro.scale_factor_stddev = *o.gyro_scale_stddev;
  // One gyro calibrated once, as a robot would be, then driven with new seeds.
  const GyroCalibration calibration = calibrateSimulatedGyro(gyro, 2024).calibration;
  std::vector<double> filtered, returned, raw;
  std::printf("%6s %9s %10s %12s %12s %12s\n", "seed", "time [s]", "path [m]", "return [m]",
              "filtered [m]", "enc. DR [m]");
  for (int i = 0; i < o.seeds; ++i) {
    DrLoopConfig c;
    c.seed = o.seed + static_cast<std::uint64_t>(i);
    c.gyro = gyro;
    c.calibration = calibration;
    const DrLoopResult r = runDrLoop(c);
    filtered.push_back(r.filtered_error_m);
    returned.push_back(r.return_to_start_m);
    raw.push_back(r.unfiltered_error_m);
    std::printf("%6llu %9.1f %10.2f %12.3f %12.3f %12.3f%s\n",
                static_cast<unsigned long long>(c.seed), r.duration_s, r.distance_m,
                r.return_to_start_m, r.filtered_error_m, r.unfiltered_error_m,
                r.mode == DrFilterMode::kFallback ? "  (fall-back)" : "");
    if (csv.is_open()) {
      csv << c.seed << "," << r.completed << "," << r.duration_s << "," << r.distance_m << ","
          << r.return_to_start_m << "," << r.filtered_error_m << "," << r.unfiltered_error_m << ","
          << radToDeg(r.filtered_heading_error_rad) << ","
          << radToDeg(r.unfiltered_heading_error_rad) << "," << r.true_right_scale_error << ","
          << r.true_left_scale_error << "," << r.true_wheelbase_error_m << ","
          << r.final_model.right_scale << "," << r.final_model.left_scale << ","
          << r.final_model.wheelbase_m << "," << r.final_model.gyro_scale << ","
          << radToDeg(r.final_model.gyro_bias_radps) * 3600.0 << ","
          << (r.mode == DrFilterMode::kFallback ? "fallback" : "filtering") << "," << r.updates
          << "," << r.gated << "," << r.mean_nis << "\n";
    }
    if (trace.is_open()) {
      for (const DrTracePoint& p : r.trace) {
        trace << c.seed << "," << p.time_s << "," << p.truth.x << "," << p.truth.y << ","
              << p.truth.theta << "," << p.filtered.x << "," << p.filtered.y << ","
              << p.filtered.theta << "," << p.unfiltered.x << "," << p.unfiltered.y << ","
              << p.unfiltered.theta;
        for (int s = 0; s < kDrStates; ++s)
          trace << "," << p.sigma(s);
        trace << "\n";
      }
    }
  }
  std::printf("median: return to start %.3f m, filtered %.3f m, encoder DR %.3f m (ratio %.1f)\n",
              median(returned), median(filtered), median(raw),
              median(raw) / std::max(median(filtered), 1e-12));
  if ((csv.is_open() && !csv) || (trace.is_open() && !trace)) {
    std::cerr << "irgs-observability: writing the CSV output failed\n";
    return 1;
  }
  return 0;
}

int calibrate(const Options& o) {
  const GyroErrorModel m = autogyroErrorModel();
  const GyroCalibrationRun run = calibrateSimulatedGyro(m, o.seed);
  for (const std::string& d : run.scale_fit.diagnostics)
    std::cout << "scale-factor fit: " << d << "\n";
  for (const std::string& d : run.bias_fit.diagnostics)
    std::cout << "bias fit: " << d << "\n";
  std::printf("rate table: %zu samples, cubic (6) fit rms %.4f deg/s\n", run.scale_fit.used,
              run.scale_fit.rms_residual_dps);
  std::printf("  a1 %.6g (true %.6g)  a2 %.6g (true %.6g)  a3 %.6g (true %.6g)\n",
              run.calibration.scale.a1, m.sf_a1, run.calibration.scale.a2_per_dps, m.sf_a2_per_dps,
              run.calibration.scale.a3_per_dps2, m.sf_a3_per_dps2);
  std::printf("temperature run: %zu samples, bias line fit rms %.4f deg/s\n", run.bias_fit.used,
              run.bias_fit.rms_residual_dps);
  std::printf("  c0 %.6g deg/s (true %.6g)  c1 %.6g deg/s/C (true %.6g)\n",
              run.calibration.bias.c0_dps, m.bias_c0_dps, run.calibration.bias.c1_dps_per_c,
              m.bias_c1_dps_per_c);
  return run.scale_fit.ok && run.bias_fit.ok ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Options o = parse(argc, argv);
    switch (o.mode) {
      case Options::Mode::kObservability:
        return observability(o);
      case Options::Mode::kLoop:
        return loop(o);
      case Options::Mode::kCalibrate:
        return calibrate(o);
    }
  } catch (const UsageError& e) {
    std::cerr << "irgs-observability: " << e.message << "\n" << kUsage;
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "irgs-observability: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
