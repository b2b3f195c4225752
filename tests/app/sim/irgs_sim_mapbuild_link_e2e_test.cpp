// Issue 4 acceptance, end to end: the same map-building scenario (thesis_arena_250.json, the
// map's start pose, noise off) run in-process (`irgs-sim --behaviour mapbuild --ideal`) and
// through `irgs-robot --ideal` over a pty (`irgs-sim --connect serial://PTY --behaviour mapbuild`)
// builds the same map. The link run is scored against the in-process map (--compare: F1 of the
// occupied cells, 2-cell tolerance, core/mapping/map_score) and both against ground truth.
//
// The link run is not bit-identical to the in-process one: the behaviour sees 20 Hz telemetry
// instead of every 10 ms simulator step, its commands reach the robot one link delay (and up to
// one 10 ms robot step) later, MANUAL_CONTROL quantises them to 1/1000 of the top speed, and the
// sample times depend on the scheduling of two processes. Turns end a little apart, and the
// decision at the end of the initial scan can flip: in the measured runs the in-process robot
// first traced the obstacle (recognised it as one, then went to the wall; 146 s) while the
// linked robot went to the wall first and met the obstacle from the interior (110-125 s). Both
// close the same outline with one obstacle. Measured (docs/map-building.md, "Over the link"),
// four link runs: F1 link vs in-process 0.992, 0.994, 0.981, 0.997; link vs truth 0.982, 0.983,
// 0.965, 0.985 (in-process 0.989; the lowest pair with a second link run beside it).
// Moving the link map rigidly shows what a broken frame costs: 5 cm -> 0.985, 10 cm -> 0.946,
// 15 cm -> 0.80; 3 deg -> 0.988, 5 deg -> 0.954, 10 deg -> 0.78. kMinAgreementF1 = 0.93 fails a
// frame error beyond about 12 cm or 6 deg and anything grosser (lost or misplaced sonar, broken
// unit conversions), leaving 0.05 below the worst measured run for timing and machine load. A
// broken command path does not finish (checked) or traces another outline (checked).
//
// Issue 24: irgs-robot counts the MANUAL_CONTROLs as they arrive (its exit summary): map building
// answers every 20 Hz sample, and at most 20 a second may reach the robot.
//
// Wall time: ~2 min (map building takes 110-146 s of robot time; the link runs in real time).
//
// Issue 24, behind a late link: the same room through irgs-linkem, 150 ms + uniform 0-100 ms of
// delay each way (the measurement: map building never left "seek wall", 0.00 m in
// 900 s). MAVLink at 115200 baud: the firmware runs the primitives; ARCOS at 9600 baud: the
// ground station supervises them with VEL/HEAD/RVEL (docs/pioneer.md). Both must finish with a
// map as good as in-process (F1 >= 0.9 vs truth, >= kMinAgreementF1 vs the in-process map),
// within the baud budget both ways (the relay counts the bytes), within 1.5x the in-process
// time (issue 24's acceptance). Measured 2026-12-07, these tests (noise off): MAVLink 113.5 s vs
// 121.7 s in-process (0.93x), F1 0.995; ARCOS 210.0 s vs 154.0 s (1.36x), F1 0.980 (2.05x
// before HEAD took the wall follower's corrections too, arcos_motion.hpp).

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "tests/app/sim/child_process.hpp"

namespace {

namespace fs = std::filesystem;
using irgs::test::Child;

constexpr double kMinAgreementF1 = 0.93;  // see the file comment
constexpr double kMinTruthF1 = 0.9;       // issue 4: >= 0.9 noise-free, for either path
constexpr double kRobotTimeBudget_s = 240.0;

nlohmann::json readJson(const fs::path& path) {
  std::ifstream in(path);
  if (!in)
    return nlohmann::json();
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception&) {
    return nlohmann::json();
  }
}

double f1Of(const nlohmann::json& metrics, const char* key) {
  const auto* node = metrics.is_object() && metrics.contains(key) ? &metrics[key] : nullptr;
  return node && node->contains("f1") ? (*node)["f1"].get<double>() : -1.0;
}

class MapBuildingOverTheLink : public ::testing::Test {
 protected:
  void SetUp() override {
    work_ = fs::temp_directory_path() / ("irgs_mapbuild_link_" + std::to_string(::getpid()));
    fs::remove_all(work_);
    fs::create_directories(work_);
  }
  void TearDown() override {
    if (!HasFailure())
      fs::remove_all(work_);  // kept on failure, for the grids and logs
  }
  fs::path work_;
};

TEST_F(MapBuildingOverTheLink, BuildsTheSameMapAsTheInProcessRun) {
  const std::string map = std::string(IRGS_SOURCE_DIR) + "/resources/maps/thesis_arena_250.json";
  const fs::path local = work_ / "in_process";
  const fs::path linked = work_ / "linked";
  const fs::path pty = work_ / "robot";

  // 1. In-process: the simulator steps as fast as it can.
  Child in_process({IRGS_SIM_EXE, "--map", map, "--behaviour", "mapbuild", "--ideal", "--out",
                    local.string(), "--quiet"});
  ASSERT_TRUE(in_process.started());
  ASSERT_EQ(in_process.wait(120.0), 0) << in_process.output();
  const nlohmann::json local_metrics = readJson(local / "metrics.json");
  ASSERT_TRUE(local_metrics.is_object()) << "no metrics.json from the in-process run";

  // 2. The same scenario through irgs-robot on a pty (MAVLink at 115200 baud).
  auto robot = std::make_unique<Child>(
      std::vector<std::string>{IRGS_ROBOT_EXE, "--map", map, "--ideal", "--link", pty.string()});
  ASSERT_TRUE(robot->started());
  ASSERT_TRUE(robot->waitOutput("/dev/pts/", 20.0)) << robot->output();
  char budget[32];
  std::snprintf(budget, sizeof budget, "%.0f", kRobotTimeBudget_s);
  Child sim({IRGS_SIM_EXE, "--connect", "serial://" + pty.string() + "?baud=115200", "--map", map,
             "--behaviour", "mapbuild", "--compare", (local / "grid.yaml").string(), "--duration",
             budget, "--out", linked.string()});
  ASSERT_TRUE(sim.started());
  const int code = sim.wait(kRobotTimeBudget_s + 40.0);
  EXPECT_EQ(robot->wait(0.0), -1) << "irgs-robot died: " << robot->output();
  robot->signal(SIGTERM);
  EXPECT_EQ(robot->wait(10.0), 0) << robot->output();
  ASSERT_EQ(code, 0) << sim.output();
  const std::string& wire = robot->output();
  const auto summary = wire.find("wire: MANUAL_CONTROL");
  ASSERT_NE(summary, std::string::npos) << wire;
  const auto peak = wire.find("peak ", summary);
  ASSERT_NE(peak, std::string::npos) << wire;
  std::printf("%s", wire.substr(summary).c_str());
  EXPECT_LE(std::strtod(wire.c_str() + peak + 5, nullptr), 20.0) << wire.substr(summary);

  const nlohmann::json link_metrics = readJson(linked / "metrics.json");
  ASSERT_TRUE(link_metrics.is_object()) << "no metrics.json from the link run";
  for (const auto* m : {&local_metrics, &link_metrics}) {
    EXPECT_TRUE((*m)["behaviour"]["finished"].get<bool>());
    EXPECT_FALSE((*m)["behaviour"]["failed"].get<bool>()) << (*m)["behaviour"]["message"];
  }
  for (const char* name :
       {"grid.pgm", "grid.yaml", "grid.png", "trajectory.csv", "indices.csv", "link.json"})
    EXPECT_TRUE(fs::exists(linked / name)) << name;

  const double local_truth = f1Of(local_metrics, "map_score");
  const double link_truth = f1Of(link_metrics, "map_score");
  const double agreement = f1Of(link_metrics, "map_agreement");
  const double local_s = local_metrics["duration_s"].get<double>();
  const double link_s = link_metrics["duration_s"].get<double>();
  std::printf(
      "measured: F1 vs truth in-process %.4f, link %.4f; F1 link vs in-process %.4f; "
      "duration %.1f s vs %.1f s; distance %.2f m vs %.2f m; indices %d vs %d\n",
      local_truth, link_truth, agreement, local_s, link_s,
      local_metrics["distance_travelled_m"].get<double>(),
      link_metrics["distance_travelled_m"].get<double>(),
      local_metrics["map_building"]["indices"].get<int>(),
      link_metrics["map_building"]["indices"].get<int>());
  RecordProperty("f1_link_vs_in_process", std::to_string(agreement));
  RecordProperty("f1_link_vs_truth", std::to_string(link_truth));
  EXPECT_GE(local_truth, kMinTruthF1);
  EXPECT_GE(link_truth, kMinTruthF1);
  EXPECT_GE(agreement, kMinAgreementF1) << link_metrics["map_agreement"].dump();
  // Same room: the same outline and the same obstacles, whichever was traced first.
  const auto& local_mb = local_metrics["map_building"];
  const auto& link_mb = link_metrics["map_building"];
  EXPECT_EQ(link_mb["obstacles"], local_mb["obstacles"]);
  const double local_area = local_mb["outline_area_m2"].get<double>();
  EXPECT_NEAR(link_mb["outline_area_m2"].get<double>(), local_area, 0.1 * local_area);
}

// The number after `key` in `text` (0 when absent).
double numberAfter(const std::string& text, const std::string& key) {
  const auto at = text.find(key);
  return at == std::string::npos ? 0.0 : std::strtod(text.c_str() + at + key.size(), nullptr);
}

struct LateLinkCase {
  std::string robot_profile;  // empty: the default robot
  bool arcos = false;
  int baud = 115200;
};

void buildBehindALateLink(const fs::path& work, const LateLinkCase& c) {
  const std::string map = std::string(IRGS_SOURCE_DIR) + "/resources/maps/thesis_arena_250.json";
  std::vector<std::string> profile;
  if (!c.robot_profile.empty())
    profile = {"--robot", std::string(IRGS_SOURCE_DIR) + "/resources/robots/" + c.robot_profile};
  const auto with = [&profile](std::vector<std::string> args) {
    args.insert(args.end(), profile.begin(), profile.end());
    return args;
  };
  const fs::path local = work / "in_process";
  const fs::path linked = work / "linked";
  Child in_process(with({IRGS_SIM_EXE, "--map", map, "--behaviour", "mapbuild", "--ideal", "--out",
                         local.string(), "--quiet"}));
  ASSERT_EQ(in_process.wait(120.0), 0) << in_process.output();
  const nlohmann::json local_metrics = readJson(local / "metrics.json");
  ASSERT_TRUE(local_metrics.is_object());

  const std::string baud = std::to_string(c.baud);
  // --baud: the robot's serial line behind the relay (the strict Pioneer takes what arrives at
  // that line's byte time).
  std::vector<std::string> robot_args = {IRGS_ROBOT_EXE, "--map",       map,      "--ideal",
                                         "--tcp",        "127.0.0.1:0", "--baud", baud};
  if (c.arcos)
    robot_args.insert(robot_args.end(), {"--protocol", "arcos", "--strict"});
  auto robot = std::make_unique<Child>(with(robot_args));
  ASSERT_TRUE(robot->waitOutput("tcp ", 20.0)) << robot->output();
  ASSERT_TRUE(robot->waitOutput("\n", 5.0));
  const int robot_port = static_cast<int>(numberAfter(robot->output(), "tcp "));
  ASSERT_GT(robot_port, 0) << robot->output();
  Child linkem({IRGS_LINKEM_EXE, "--listen", "127.0.0.1:0", "--connect",
                "127.0.0.1:" + std::to_string(robot_port), "--delay-ms", "150", "--jitter-ms",
                "100", "--baud", baud, "--seed", "1"});
  ASSERT_TRUE(linkem.waitOutput(", relaying", 10.0)) << linkem.output();
  const int link_port = static_cast<int>(numberAfter(linkem.output(), "127.0.0.1:"));
  ASSERT_GT(link_port, 0) << linkem.output();

  const std::string url = "tcp://127.0.0.1:" + std::to_string(link_port) + "?baud=" + baud +
                          (c.arcos ? "&protocol=arcos" : "");
  Child sim(
      with({IRGS_SIM_EXE, "--connect", url, "--map", map, "--behaviour", "mapbuild", "--compare",
            (local / "grid.yaml").string(), "--duration", "600", "--out", linked.string()}));
  const int code = sim.wait(660.0);
  ASSERT_TRUE(linkem.waitOutput("closed:", 10.0)) << linkem.output();
  robot->signal(SIGTERM);
  robot->wait(10.0);
  linkem.signal(SIGTERM);
  linkem.wait(5.0);
  ASSERT_EQ(code, 0) << sim.output();

  const nlohmann::json link_metrics = readJson(linked / "metrics.json");
  ASSERT_TRUE(link_metrics.is_object());
  EXPECT_TRUE(link_metrics["behaviour"]["finished"].get<bool>());
  EXPECT_FALSE(link_metrics["behaviour"]["failed"].get<bool>()) << link_metrics["behaviour"];
  const double local_s = local_metrics["duration_s"].get<double>();
  const double link_s = link_metrics["duration_s"].get<double>();
  // "to robot N bytes (...), to ground station M bytes": what the relay carried.
  const std::string& relay = linkem.output();
  const double up_bps = numberAfter(relay, "to robot ") / link_s;
  const double down_bps = numberAfter(relay, "to ground station ") / link_s;
  const double budget_bps = c.baud / 10.0;
  std::printf(
      "behind 150 ms + 0-100 ms at %d baud (%s): %.1f s vs %.1f s in-process (%.2fx); F1 vs "
      "truth %.4f (in-process %.4f), vs in-process %.4f; uplink %.0f B/s, downlink %.0f B/s of "
      "%.0f\n%s",
      c.baud, c.arcos ? "ARCOS" : "MAVLink", link_s, local_s, link_s / local_s,
      f1Of(link_metrics, "map_score"), f1Of(local_metrics, "map_score"),
      f1Of(link_metrics, "map_agreement"), up_bps, down_bps, budget_bps, robot->output().c_str());
  EXPECT_GE(f1Of(link_metrics, "map_score"), kMinTruthF1);
  EXPECT_GE(f1Of(link_metrics, "map_agreement"), kMinAgreementF1);
  EXPECT_LE(up_bps, 0.5 * budget_bps);  // commands: at most half the link
  EXPECT_LE(down_bps, budget_bps);
  EXPECT_LE(link_s, 1.5 * local_s);
  if (c.arcos) {  // "taken N, lost too soon M, ...": nothing lost for the link's jitter
    ASSERT_NE(robot->output().find("lost too soon "), std::string::npos) << robot->output();
    EXPECT_EQ(numberAfter(robot->output(), "lost too soon "), 0.0) << robot->output();
  }
}

TEST_F(MapBuildingOverTheLink, CompletesBehindALateLinkOverMavlink) {
  buildBehindALateLink(work_, {"", false, 115200});
}

TEST_F(MapBuildingOverTheLink, CompletesBehindALateLinkOverArcos) {
  buildBehindALateLink(work_, {"pioneer_amigo.json", true, 9600});
}

}  // namespace
