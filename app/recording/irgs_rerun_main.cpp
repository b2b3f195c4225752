// irgs-rerun: re-runs a session recording's sensor stream through the mapper and an estimator
// with changed parameters and compares the result with the recorded run (issue 6 item 3,
// docs/gui.md "Re-run with parameters").
//   irgs-rerun RECORDING [--param NAME=VALUE ...] [--robot FILE] [--map FILE] --out DIR
//   irgs-rerun --list-params
// Writes both grids (PNG, ROS map), both trajectories (CSV) and metrics.json into DIR and prints
// a one-line summary. Exit status 0 on success, 1 when the recording cannot be re-run or the
// outputs not written, 2 for bad arguments.

#include <QCoreApplication>
#include <QDir>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "app/recording/recording_reader.hpp"
#include "app/recording/rerun_engine.hpp"
#include "app/recording/rerun_inputs.hpp"
#include "app/recording/rerun_output.hpp"
#include "app/recording/rerun_parameters.hpp"

namespace {

namespace rec = irgs::recording;

void usage(std::FILE* out) {
  std::fprintf(out,
               "usage: irgs-rerun RECORDING [--param NAME=VALUE ...] [--robot FILE] [--map FILE]\n"
               "                  --out DIR\n"
               "       irgs-rerun --list-params\n"
               "  Decodes the recording's link bytes as a live link does, maps them (and runs\n"
               "  an estimator) once with the recorded parameters and once with the --param\n"
               "  changes, and writes recorded_/rerun_map.png|.yaml|.pgm, recorded_/\n"
               "  rerun_trajectory.csv and metrics.json into DIR.\n");
}

void listParameters() {
  const rec::RerunParameters defaults;
  for (const rec::RerunParameterInfo& info : rec::rerunParameters()) {
    std::string values;  // the choices, or the default
    if (!info.choices.empty()) {
      for (const std::string& c : info.choices)
        values += (values.empty() ? "" : "|") + c;
    } else {
      values = rec::rerunParameterValue(defaults, info.name) + " (default)";
    }
    std::printf("%-24s %-8s %-30s %s\n", info.name.c_str(), info.unit.c_str(), values.c_str(),
                info.description.c_str());
  }
}

std::vector<std::filesystem::path> resourceDirs(const char* argv0) {
  std::vector<std::filesystem::path> dirs;
  if (const char* env = std::getenv("IRGS_RESOURCE_DIR"); env != nullptr && *env != '\0')
    dirs.emplace_back(env);
  std::error_code ec;
  const auto exe = std::filesystem::canonical("/proc/self/exe", ec);
  if (!ec)
    dirs.push_back(exe.parent_path() / ".." / "share" / "irgs" / "resources");
  (void)argv0;
#ifdef IRGS_RESOURCE_DIR
  dirs.emplace_back(IRGS_RESOURCE_DIR);
#endif
  return dirs;
}

}  // namespace

int main(int argc, char** argv) {
  std::string input, out_dir, robot_file, map_file;
  std::vector<std::string> assignments;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&](std::string& into) {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "irgs-rerun: %s needs a value\n", arg.c_str());
        return false;
      }
      into = argv[++i];
      return true;
    };
    if (arg == "--help" || arg == "-h") {
      usage(stdout);
      return 0;
    } else if (arg == "--list-params") {
      listParameters();
      return 0;
    } else if (arg == "--param") {
      std::string a;
      if (!value(a))
        return 2;
      assignments.push_back(a);
    } else if (arg == "--out") {
      if (!value(out_dir))
        return 2;
    } else if (arg == "--robot") {
      if (!value(robot_file))
        return 2;
    } else if (arg == "--map") {
      if (!value(map_file))
        return 2;
    } else if (!arg.empty() && arg[0] == '-') {
      std::fprintf(stderr, "irgs-rerun: unknown option %s\n", arg.c_str());
      usage(stderr);
      return 2;
    } else if (input.empty()) {
      input = arg;
    } else {
      std::fprintf(stderr, "irgs-rerun: more than one recording given\n");
      return 2;
    }
  }
  if (input.empty() || out_dir.empty()) {
    usage(stderr);
    return 2;
  }

  QCoreApplication app(argc, argv);  // Qt Sql loads its driver through the application
  rec::LoadResult loaded = rec::loadRecording(input);
  if (!loaded.recording) {
    std::fprintf(stderr, "irgs-rerun: %s\n", loaded.error.c_str());
    return 1;
  }
  for (const std::string& warning : loaded.warnings)
    std::fprintf(stderr, "irgs-rerun: warning: %s\n", warning.c_str());
  const rec::Recording& recording = *loaded.recording;

  std::vector<std::string> warnings;
  const rec::RerunParameters recorded = rec::recordedRerunParameters(recording.meta, &warnings);
  rec::RerunParameters changed = recorded;
  for (const std::string& a : assignments) {
    if (const auto error = rec::setRerunParameterAssignment(changed, a)) {
      std::fprintf(stderr, "irgs-rerun: --param %s\n", error->c_str());
      return 2;
    }
  }
  rec::RerunInputs inputs =
      rec::resolveRerunInputs(recording, robot_file, map_file, resourceDirs(argv[0]));
  warnings.insert(warnings.end(), inputs.warnings.begin(), inputs.warnings.end());
  for (const std::string& warning : warnings)
    std::fprintf(stderr, "irgs-rerun: warning: %s\n", warning.c_str());
  if (!inputs.profile) {
    std::fprintf(stderr, "irgs-rerun: %s\n", inputs.error.c_str());
    return 1;
  }

  const auto start = std::chrono::steady_clock::now();
  const rec::RerunResult result =
      rec::rerunRecording(recording, *inputs.profile, inputs.map, recorded, changed);
  const double elapsed_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!result.error.empty()) {
    std::fprintf(stderr, "irgs-rerun: %s: %s\n", input.c_str(), result.error.c_str());
    return 1;
  }
  const std::string name = std::filesystem::path(input).filename().string();
  if (const std::string error = rec::writeRerunOutputs(result, out_dir, name); !error.empty()) {
    std::fprintf(stderr, "irgs-rerun: %s\n", error.c_str());
    return 1;
  }
  const irgs::GridComparison& g = result.metrics.grid;
  std::printf(
      "%s: %zu samples in %.2f s; grid agreement %.4f (%zu cells), occupied F1 %.4f (within %d "
      "cells %.4f)%s; pose difference rms %.4f m, max %.4f m\n",
      name.c_str(), result.samples, elapsed_s, g.agreement, g.compared_cells, g.occupied.f1,
      irgs::GridCompareOptions{}.tolerance_cells, g.occupied_tolerant.f1,
      g.identical ? ", identical" : "", result.metrics.pose.rms_position_m,
      result.metrics.pose.max_position_m);
  return 0;
}
