// irgs-sim: runs a scenario headless and writes its outputs (see --help).

#include <signal.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "app/sim/behaviour_run.hpp"
#include "app/sim/delivery_run.hpp"
#include "app/sim/linked_run.hpp"
#include "app/sim/localization_run.hpp"
#include "app/sim/sim_options.hpp"
#include "comms/mavlink/signing_key.hpp"
#include "core/io/atomic_file.hpp"
#include "core/robot/robot_profile_file.hpp"
#include "core/scenario/scenario_outputs.hpp"
#include "core/scenario/scenario_runner.hpp"
#include "core/sim/drive_script.hpp"
#include "core/world/map_file.hpp"
#include "core/world/ros_map.hpp"

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

// ---- --connect: the same run against a linked robot (app/sim/linked_run.hpp) ----

constexpr int kExitLink = 3;
constexpr int kExitInterrupted = 130;
std::atomic<bool> g_interrupted{false};  // lock-free: safe to set from a signal handler

extern "C" void onInterrupt(int) {
  g_interrupted.store(true);
}

void printOutcome(const irgs::app::BehaviourRunOutcome& outcome, bool quiet) {
  if (!outcome.error.empty())
    std::fprintf(stderr, "irgs-sim: %s\n", outcome.error.c_str());
  if (!quiet || outcome.exit_code != 0) {
    if (!outcome.summary.empty())
      std::printf("irgs-sim: %s\n", outcome.summary.c_str());
    if (!quiet)
      for (const auto& path : outcome.written)
        std::printf("  wrote %s\n", path.string().c_str());
  }
}

// --compare names a map an earlier run saved: read it before driving anything, so a typo costs
// nothing (the run itself may take minutes on a linked robot).
bool compareReferenceReadable(const irgs::app::SimOptions& options) {
  if (options.compare.empty())
    return true;
  const auto reference = irgs::loadRosMap(options.compare);
  if (reference.raster)
    return true;
  printDiagnostics(reference.diagnostics);
  std::fprintf(stderr, "irgs-sim: cannot read the --compare map %s\n",
               options.compare.string().c_str());
  return false;
}

double wallSeconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

int runConnected(const irgs::app::SimOptions& options, const char* argv0) {
  const auto robot_path = options.robot.empty() ? bundledRobotProfile(argv0) : options.robot;
  auto robot = irgs::loadRobotProfileFile(robot_path);
  printDiagnostics(robot.diagnostics);
  if (!robot.profile) {
    std::fprintf(stderr, "irgs-sim: cannot load robot profile %s\n", robot_path.string().c_str());
    return kExitFiles;
  }
  // The map, when given, is the frame the robot starts in (--start or its start pose), what
  // goal and coverage plan on and what the built map is scored against.
  std::optional<irgs::WorldMap> map;
  if (!options.map.empty()) {
    auto loaded = irgs::loadAnyMap(options.map);
    printDiagnostics(loaded.diagnostics);
    if (!loaded.map) {
      std::fprintf(stderr, "irgs-sim: cannot load map %s\n", options.map.string().c_str());
      return kExitFiles;
    }
    map = std::move(*loaded.map);
  }
  irgs::app::LinkedRunSpec spec;
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
  spec.url = options.connect;
  spec.profile = *robot.profile;
  spec.anchor =
      options.start ? options.start : (map ? std::optional<irgs::Pose2>(map->start) : std::nullopt);
  if (!compareReferenceReadable(options))
    return kExitFiles;
  irgs::app::BehaviourJob job;
  if (!options.behaviour.empty()) {
    const irgs::Pose2 start = spec.anchor.value_or(irgs::Pose2{});
    if (const auto error = irgs::app::prepareBehaviourJob(options, map ? &*map : nullptr,
                                                          spec.profile, start, job)) {
      std::fprintf(stderr, "irgs-sim: %s\n", error->c_str());
      return kExitLink;  // the behaviour could not start: nothing was driven
    }
    spec.behaviour = job.mission.get();
    spec.duration_s = options.duration_s.value_or(3600.0);
  } else {
    spec.duration_s = options.duration_s.value_or(
        spec.script.empty() ? 60.0 : std::max(spec.script.lastTime_s(), 0.1));
  }
  spec.connect_timeout_s = options.connect_timeout_s;
  if (!options.signing_key.empty()) {
    const auto key = irgs::comms::mavlink::loadSigningKeyFile(options.signing_key);
    if (!key.key) {
      std::fprintf(stderr, "irgs-sim: %s\n", key.error.c_str());
      return kExitFiles;
    }
    spec.signing_key = key.key;
  }
  spec.grid_resolution_m = options.grid_resolution_m;
  spec.cancel = &g_interrupted;
  spec.wall_clock = wallSeconds;
  if (!options.quiet)
    spec.log = [](const std::string& line) {
      std::printf("irgs-sim: %s\n", line.c_str());
      std::fflush(stdout);  // live progress also when stdout is a pipe or a log file
    };

  struct sigaction action {};
  action.sa_handler = onInterrupt;
  sigemptyset(&action.sa_mask);
  ::sigaction(SIGINT, &action, nullptr);
  ::sigaction(SIGTERM, &action, nullptr);

  irgs::app::LinkedRunResult run = irgs::app::runLinkedScenario(spec);
  if (!run.result) {
    std::fprintf(stderr, "irgs-sim: %s\n", run.error.c_str());
    return run.cancelled ? kExitInterrupted : kExitLink;
  }
  const std::string map_name =
      options.map.empty() ? "linked robot" : options.map.filename().string();
  const irgs::ScenarioRunInfo info{map_name + " via " + options.connect, spec.profile.name,
                                   options.seed};
  const std::string link_json = irgs::app::linkedRunJson(spec, run);

  if (spec.behaviour) {
    irgs::BehaviourScenarioResult result{std::move(*run.result), run.behaviour};
    irgs::app::BehaviourOutputInfo out_info;
    out_info.run = info;
    out_info.truth = map ? &*map : nullptr;
    out_info.clock = "of robot time";
    out_info.extra_files = {{"link.json", link_json}};
    out_info.extra["link"] = {{"protocol", run.protocol},
                              {"truth", "odometry (no ground truth from a linked robot)"}};
    const auto outcome = irgs::app::writeBehaviourOutputs(options, job, result, out_info);
    printOutcome(outcome, options.quiet);
    if (outcome.exit_code == kExitFiles)
      return kExitFiles;
    return run.cancelled ? kExitInterrupted : outcome.exit_code;
  }

  auto written = irgs::writeScenarioOutputs(*run.result, info, options.out);
  if (written.error.empty()) {
    const std::filesystem::path target = options.out / "link.json";
    if (const auto error = irgs::writeFileAtomically(target, link_json))
      written.error = *error;
    else
      written.written.push_back(target);
  }
  if (!written.error.empty()) {
    std::fprintf(stderr, "irgs-sim: %s\n", written.error.c_str());
    return kExitFiles;
  }
  if (!options.quiet) {
    const auto& m = run.result->metrics;
    std::printf(
        "irgs-sim: %.1f s on %s (%s), %llu samples, %.2f m driven (odometry), explored %.2f "
        "m2%s\n"
        "  no ground truth from a linked robot: true_* columns repeat the odometry\n",
        m.duration_s, options.connect.c_str(), run.protocol.c_str(),
        static_cast<unsigned long long>(run.samples), m.distance_travelled_m, m.explored_area_m2,
        run.cancelled ? " (interrupted)" : "");
    for (const auto& path : written.written)
      std::printf("  wrote %s\n", path.string().c_str());
  }
  return run.cancelled ? kExitInterrupted : 0;
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
  if (!options.connect.empty())
    return runConnected(options, argv[0]);

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

  if (!options.localize.empty()) {
    const auto outcome = irgs::app::runLocalizationMode(options, *map.map, *robot.profile);
    if (!outcome.error.empty())
      std::fprintf(stderr, "irgs-sim: %s\n", outcome.error.c_str());
    if (!options.quiet && !outcome.summary.empty()) {
      std::printf("irgs-sim: %s\n", outcome.summary.c_str());
      for (const auto& path : outcome.written)
        std::printf("  wrote %s\n", path.string().c_str());
    }
    return outcome.exit_code;
  }

  if (options.behaviour == "deliver") {
    const auto outcome = irgs::app::runDeliveryMode(options, *map.map, *robot.profile, wallSeconds);
    printOutcome(outcome, options.quiet);
    return outcome.exit_code;
  }

  if (!options.behaviour.empty()) {
    if (!compareReferenceReadable(options))
      return kExitFiles;
    const auto outcome =
        irgs::app::runBehaviourMode(options, *map.map, *robot.profile, wallSeconds);
    printOutcome(outcome, options.quiet);
    return outcome.exit_code;
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
