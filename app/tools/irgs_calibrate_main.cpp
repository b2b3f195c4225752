// irgs-calibrate: the calibration wizards of the GUI without a display (docs/calibration.md).
//   umbmark  UMBmark (Borenstein & Feng): in the simulator with injected wheel-diameter and
//            wheelbase errors (--inject), or from return errors measured on a real floor
//            (--measured FILE); the corrections are written into a copy of the profile (--out).
//   gyro     001_…'s gyro calibration: in the simulator with an injected gyro (--inject), or
//            from a real robot's rate-table and stationary logs (--rate-log, --rest-log).
// The same core code as the GUI wizards (core/calibration). Exit codes: 0 success, 1 the
// procedure failed or a file could not be read or written, 2 usage error.

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "core/calibration/gyro_calibration_run.hpp"
#include "core/calibration/profile_calibration.hpp"
#include "core/calibration/umbmark_procedure.hpp"
#include "core/io/atomic_file.hpp"
#include "core/robot/robot_profile_file.hpp"
#include "core/sim/gyro_sim.hpp"

namespace {

using namespace irgs;

constexpr const char* kUsage =
    "usage: irgs-calibrate umbmark --profile P --out P2\n"
    "                      [--inject ed=E_D,eb=E_B[,slip=S]] [--runs N] [--side M] [--seed S]\n"
    "                      [--measured FILE]   (real floor: lines 'cw|ccw, x_m, y_m')\n"
    "       irgs-calibrate gyro --profile P --out P2\n"
    "                      [--inject autogyro[,c0=..,c1=..,c2=..,a1=..,a2=..,a3=..]]\n"
    "                      [--bias-order 1|2] [--turn-ons N] [--seed S]\n"
    "                      [--rate-log FILE --rest-log FILE]   (real robot logs, CSV)\n";

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

int integer(const std::string& option, const std::string& text, int lo, int hi) {
  const double v = number(option, text);
  if (v < lo || v > hi || v != std::floor(v))
    throw UsageError{option + " must be an integer in [" + std::to_string(lo) + ", " +
                     std::to_string(hi) + "]"};
  return static_cast<int>(v);
}

// "a=1,b=2" -> {a: "1", b: "2"}; a bare word (no '=') maps to "".
std::map<std::string, std::string> keyValues(const std::string& option, const std::string& text) {
  std::map<std::string, std::string> out;
  std::istringstream in(text);
  for (std::string item; std::getline(in, item, ',');) {
    if (item.empty())
      throw UsageError{option + ": empty item in '" + text + "'"};
    const auto eq = item.find('=');
    out[item.substr(0, eq)] = eq == std::string::npos ? std::string() : item.substr(eq + 1);
  }
  return out;
}

struct Options {
  std::string mode;
  std::string profile;
  std::string out;
  std::string inject;
  std::string measured;
  std::string rate_log;
  std::string rest_log;
  int runs = 5;
  double side_m = 4.0;
  std::uint64_t seed = 1;
  std::optional<int> bias_order;
  int turn_ons = 4;
};

Options parse(int argc, char** argv) {
  Options o;
  if (argc >= 2 && (std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h")) {
    std::cout << kUsage;
    std::exit(0);
  }
  if (argc < 2 || (std::string(argv[1]) != "umbmark" && std::string(argv[1]) != "gyro"))
    throw UsageError{"the first argument must be umbmark or gyro"};
  o.mode = argv[1];
  for (int i = 2; i < argc; ++i) {
    const std::string a = argv[i];
    const auto value = [&]() -> std::string {
      if (i + 1 >= argc)
        throw UsageError{a + " needs a value"};
      return argv[++i];
    };
    if (a == "--profile") {
      o.profile = value();
    } else if (a == "--out") {
      o.out = value();
    } else if (a == "--inject") {
      o.inject = value();
    } else if (a == "--measured" && o.mode == "umbmark") {
      o.measured = value();
    } else if (a == "--runs" && o.mode == "umbmark") {
      o.runs = integer(a, value(), 1, 100);
    } else if (a == "--side" && o.mode == "umbmark") {
      o.side_m = number(a, value());
      if (!(o.side_m > 0.0 && o.side_m <= 100.0))
        throw UsageError{"--side must be in (0, 100] m"};
    } else if (a == "--seed") {
      o.seed = static_cast<std::uint64_t>(integer(a, value(), 0, 1000000000));
    } else if (a == "--bias-order" && o.mode == "gyro") {
      o.bias_order = integer(a, value(), 1, 2);
    } else if (a == "--turn-ons" && o.mode == "gyro") {
      o.turn_ons = integer(a, value(), 1, 50);
    } else if (a == "--rate-log" && o.mode == "gyro") {
      o.rate_log = value();
    } else if (a == "--rest-log" && o.mode == "gyro") {
      o.rest_log = value();
    } else if (a == "--help" || a == "-h") {
      std::cout << kUsage;
      std::exit(0);
    } else {
      throw UsageError{"unknown option '" + a + "' for " + o.mode};
    }
  }
  if (o.profile.empty() || o.out.empty())
    throw UsageError{"--profile and --out are required"};
  if (!o.measured.empty() && !o.inject.empty())
    throw UsageError{"--measured (a real floor) and --inject (the simulator) exclude each other"};
  if (o.rate_log.empty() != o.rest_log.empty())
    throw UsageError{"--rate-log and --rest-log go together"};
  if (!o.rate_log.empty() && !o.inject.empty())
    throw UsageError{"--rate-log/--rest-log (a real robot) and --inject exclude each other"};
  return o;
}

UmbmarkInjection umbmarkInjection(const std::string& text) {
  UmbmarkInjection injection;
  for (const auto& [key, value] : keyValues("--inject", text)) {
    if (key == "ed")
      injection.wheel_diameter_ratio = number("--inject ed", value);
    else if (key == "eb")
      injection.wheelbase_scale = number("--inject eb", value);
    else if (key == "slip")
      injection.slip_stddev = number("--inject slip", value);
    else
      throw UsageError{"--inject: unknown key '" + key + "' (ed, eb, slip)"};
  }
  return injection;
}

GyroErrorModel gyroInjection(const std::string& text) {
  GyroErrorModel model = autogyroErrorModel();
  for (const auto& [key, value] : keyValues("--inject", text.empty() ? "autogyro" : text)) {
    if (key == "autogyro" && value.empty())
      continue;
    double* field = key == "c0"   ? &model.bias_c0_dps
                    : key == "c1" ? &model.bias_c1_dps_per_c
                    : key == "c2" ? &model.bias_c2_dps_per_c2
                    : key == "a1" ? &model.sf_a1
                    : key == "a2" ? &model.sf_a2_per_dps
                    : key == "a3" ? &model.sf_a3_per_dps2
                                  : nullptr;
    if (field == nullptr)
      throw UsageError{"--inject: unknown key '" + key + "' (autogyro, c0, c1, c2, a1, a2, a3)"};
    *field = number("--inject " + key, value);
  }
  return model;
}

std::optional<RobotProfile> loadProfile(const std::string& path) {
  const RobotProfileResult r = loadRobotProfileFile(path);
  for (const auto& d : r.diagnostics)
    std::cerr << "irgs-calibrate: " << d.toString() << '\n';
  if (!r.ok()) {
    std::cerr << "irgs-calibrate: error: cannot use robot profile " << path << '\n';
    return std::nullopt;
  }
  return *r.profile;
}

int save(const RobotProfile& profile, const std::string& out) {
  if (const auto error = saveCalibratedProfile(profile, out)) {
    std::cerr << "irgs-calibrate: error: " << *error << '\n';
    return 1;
  }
  std::cout << "wrote " << out << '\n';
  return 0;
}

void printAnalysis(const UmbmarkAnalysis& a) {
  std::cout << "  runs: " << a.cw_runs << " cw, " << a.ccw_runs << " ccw\n"
            << "  centre of gravity cw  (m): " << a.cg_cw.x() << ", " << a.cg_cw.y() << '\n'
            << "  centre of gravity ccw (m): " << a.cg_ccw.x() << ", " << a.cg_ccw.y() << '\n'
            << "  E_max,syst (m): " << a.e_max_syst_m << '\n';
}

int umbmark(const Options& o) {
  const std::optional<RobotProfile> profile = loadProfile(o.profile);
  if (!profile)
    return 1;
  std::cout << std::setprecision(6);
  UmbmarkProcedureResult result;
  std::optional<UmbmarkInjection> injection;
  if (!o.measured.empty()) {
    const ReadFileResult file = readFile(o.measured);
    if (!file.ok()) {
      std::cerr << "irgs-calibrate: error: " << file.error << '\n';
      return 1;
    }
    const UmbmarkRunsText parsed = parseUmbmarkRuns(file.bytes);
    for (const std::string& d : parsed.diagnostics)
      std::cerr << "irgs-calibrate: " << o.measured << ": " << d << '\n';
    std::cout << "UMBmark from measured return errors (" << o.measured << "), side " << o.side_m
              << " m\n";
    result = analyseMeasuredUmbmark(*profile, parsed.runs, o.side_m);
  } else {
    injection = umbmarkInjection(o.inject);
    UmbmarkRunConfig config;
    config.runs_per_direction = o.runs;
    config.side_m = o.side_m;
    config.seed = o.seed;
    std::cout << "UMBmark in the simulator: injected E_d = " << injection->wheel_diameter_ratio
              << ", E_b = " << injection->wheelbase_scale << ", slip " << injection->slip_stddev
              << ", " << o.runs << " + " << o.runs << " runs of " << o.side_m << " m, seed "
              << o.seed << '\n';
    try {
      result = runUmbmarkProcedureInSimulator(*profile, *injection, config, true);
    } catch (const std::invalid_argument& e) {
      throw UsageError{e.what()};
    }
  }
  for (const std::string& d : result.diagnostics)
    std::cerr << "irgs-calibrate: " << d << '\n';
  if (!result.ok) {
    std::cerr << "irgs-calibrate: error: the UMBmark analysis failed\n";
    return 1;
  }
  printAnalysis(result.analysis);
  const UmbmarkAnalysis& a = result.analysis;
  std::cout << "  wheel diameter ratio E_d: " << a.wheel_diameter_ratio << '\n'
            << "  wheelbase ratio E_b: " << a.wheelbase_ratio << '\n';
  if (injection) {
    const auto rel = [](double recovered, double injected) {
      return std::abs(recovered - injected) / std::abs(injected - 1.0) * 100.0;
    };
    if (injection->wheel_diameter_ratio != 1.0)
      std::cout << "  E_d error: " << rel(a.wheel_diameter_ratio, injection->wheel_diameter_ratio)
                << " % of the injected error\n";
    if (injection->wheelbase_scale != 1.0)
      std::cout << "  E_b error: " << rel(a.wheelbase_ratio, injection->wheelbase_scale)
                << " % of the injected error\n";
  }
  std::cout << "corrected wheelbase (m): " << result.corrected.drive.wheelbase_m << '\n';
  if (result.verification) {
    std::cout << "verification on the corrected odometry (seed " << o.seed + 1 << "):\n";
    printAnalysis(*result.verification);
    std::cout << "  E_max,syst improvement: x" << result.improvement() << '\n';
  }
  return save(result.corrected, o.out);
}

int gyro(const Options& o) {
  const std::optional<RobotProfile> profile = loadProfile(o.profile);
  if (!profile)
    return 1;
  std::cout << std::setprecision(6);
  GyroProcedureResult result;
  std::optional<GyroErrorModel> injected;
  int order = o.bias_order.value_or(1);
  if (!o.rate_log.empty()) {
    const ReadFileResult rate = readFile(o.rate_log);
    const ReadFileResult rest = readFile(o.rest_log);
    for (const ReadFileResult* f : {&rate, &rest})
      if (!f->ok()) {
        std::cerr << "irgs-calibrate: error: " << f->error << '\n';
        return 1;
      }
    std::cout << "gyro calibration from logs " << o.rate_log << ", " << o.rest_log << '\n';
    result = fitGyroCalibrationLogs(parseCalibrationCsv(rate.bytes),
                                    parseCalibrationCsv(rest.bytes), order);
  } else {
    injected = gyroInjection(o.inject);
    if (!o.bias_order && injected->bias_c2_dps_per_c2 != 0.0)
      order = 2;
    GyroProcedureConfig config;
    config.turn_ons = o.turn_ons;
    config.seed = o.seed;
    config.runs.bias_order = order;
    std::cout << "gyro calibration in the simulator: " << o.turn_ons << " power-ups, bias order "
              << order << ", seed " << o.seed << '\n';
    try {
      result = runGyroCalibrationInSimulator(*injected, config);
    } catch (const std::invalid_argument& e) {
      throw UsageError{e.what()};
    }
  }
  for (const std::string& d : result.diagnostics)
    std::cerr << "irgs-calibrate: " << d << '\n';
  if (!result.ok) {
    std::cerr << "irgs-calibrate: error: the gyro fits failed\n";
    return 1;
  }
  const GyroCalibration& c = result.calibration;
  std::cout << "  samples: " << result.rate_samples << " rate table, " << result.rest_samples
            << " stationary (" << result.rest_min_temperature_c << " .. "
            << result.rest_max_temperature_c << " C)\n"
            << "  scale factor (6): a1 = " << c.scale.a1 << ", a2 = " << c.scale.a2_per_dps
            << " 1/(deg/s), a3 = " << c.scale.a3_per_dps2 << " 1/(deg/s)^2\n"
            << "  temperature bias: c0 = " << c.bias.c0_dps
            << " deg/s, c1 = " << c.bias.c1_dps_per_c << " deg/s/C, c2 = " << c.bias.c2_dps_per_c2
            << " deg/s/C^2\n";
  if (injected) {
    const double mid = 0.5 * (result.rest_min_temperature_c + result.rest_max_temperature_c);
    for (const GyroCoefficientCheck& k : compareGyroCalibration(c, *injected, order, mid))
      std::cout << "  " << k.name << ": injected " << k.injected << ", recovered " << k.recovered
                << ", error " << k.relative_error * 100.0 << " %\n";
  }
  return save(applyGyroCalibration(*profile, c), o.out);
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Options o = parse(argc, argv);
    return o.mode == "umbmark" ? umbmark(o) : gyro(o);
  } catch (const UsageError& e) {
    std::cerr << "irgs-calibrate: " << e.message << '\n' << kUsage;
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "irgs-calibrate: error: " << e.what() << '\n';
    return 1;
  }
}
