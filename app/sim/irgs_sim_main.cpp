// irgs-sim: runs a scenario headless and writes its outputs (see --help).

#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "app/sim/sim_options.hpp"
#include "core/robot/robot_profile_file.hpp"
#include "core/scenario/scenario_outputs.hpp"
#include "core/scenario/scenario_runner.hpp"
#include "core/sim/drive_script.hpp"
#include "core/world/map_file.hpp"

namespace {

constexpr int kExitFiles = 1;
constexpr int kExitUsage = 2;

void printDiagnostics(const std::vector<irgs::Diagnostic>& diagnostics) {
  for (const auto& d : diagnostics)
    std::fprintf(stderr, "%s\n", d.toString().c_str());
}

std::filesystem::path bundledRobotProfile(const char* argv0) {
  namespace fs = std::filesystem;
  // An install keeps resources beside the executable; a build tree uses the sources it came from.
  std::error_code ec;
  const fs::path exe = fs::canonical(fs::path(argv0), ec);
  if (!ec) {
    const fs::path installed =
        exe.parent_path() / "../share/irgs/resources/robots/thesis_robot.json";
    if (fs::exists(installed, ec))
      return installed;
  }
  return fs::path(IRGS_RESOURCE_DIR) / "robots/thesis_robot.json";
}

}  // namespace

int main(int argc, char** argv) {
  const auto parsed = irgs::app::parseSimOptions(std::vector<std::string>(argv + 1, argv + argc));
  if (parsed.help) {
    std::fputs(irgs::app::simUsage().c_str(), stdout);
    return 0;
  }
  if (!parsed.options) {
    std::fprintf(stderr, "irgs-sim: %s\n", parsed.error.c_str());
    return kExitUsage;
  }
  const irgs::app::SimOptions& options = *parsed.options;

  auto map = irgs::loadAnyMap(options.map);
  printDiagnostics(map.diagnostics);
  if (!map.map) {
    std::fprintf(stderr, "irgs-sim: cannot load map %s\n", options.map.string().c_str());
    return kExitFiles;
  }

  const auto robot_path = options.robot.empty() ? bundledRobotProfile(argv[0]) : options.robot;
  auto robot = irgs::loadRobotProfileFile(robot_path);
  printDiagnostics(robot.diagnostics);
  if (!robot.profile) {
    std::fprintf(stderr, "irgs-sim: cannot load robot profile %s\n", robot_path.string().c_str());
    return kExitFiles;
  }

  irgs::ScenarioSpec spec;
  if (!options.script.empty()) {
    auto script = irgs::loadDriveScriptFile(options.script);
    printDiagnostics(script.diagnostics);
    if (!script.script) {
      std::fprintf(stderr, "irgs-sim: cannot load drive script %s\n",
                   options.script.string().c_str());
      return kExitFiles;
    }
    spec.script = std::move(*script.script);
  }
  spec.map = std::move(*map.map);
  spec.profile = std::move(*robot.profile);
  spec.start = options.start;
  spec.sim = options.ideal ? irgs::idealSimConfig(spec.sim) : irgs::typicalSimConfig(spec.sim);
  spec.sim.seed = options.seed;
  spec.duration_s = options.duration_s.value_or(
      spec.script.empty() ? 60.0 : std::max(spec.script.lastTime_s(), spec.sim.dt_s));
  spec.grid_resolution_m = options.grid_resolution_m;

  const auto started = std::chrono::steady_clock::now();
  const irgs::ScenarioResult result = irgs::runScenario(spec);
  const double wall_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();

  const irgs::ScenarioRunInfo info{options.map.filename().string(), spec.profile.name,
                                   options.seed};
  const auto written = irgs::writeScenarioOutputs(result, info, options.out);
  if (!written.error.empty()) {
    std::fprintf(stderr, "irgs-sim: %s\n", written.error.c_str());
    return kExitFiles;
  }
  if (!options.quiet) {
    const auto& m = result.metrics;
    std::printf(
        "irgs-sim: %.1f s simulated in %.2f s wall (x%.0f), %.2f m driven, "
        "odometry error %.3f m, explored %.2f m2\n",
        m.duration_s, wall_s, wall_s > 0 ? m.duration_s / wall_s : 0.0, m.distance_travelled_m,
        m.odometry_position_error_m, m.explored_area_m2);
    for (const auto& path : written.written)
      std::printf("  wrote %s\n", path.string().c_str());
  }
  return 0;
}
