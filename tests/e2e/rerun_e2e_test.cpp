// Re-run mode (issue 6 item 3), end to end: irgs records a session driving irgs-robot over a
// real pty (as recording_replay_e2e_test does), then irgs-rerun re-runs the recording:
//  * with the recorded parameters it reproduces what the live session showed exactly: the same
//    cells with the same log-odds as irgs --grid-out wrote at exit, and every live pose of
//    --trajectory-out at its robot time; metrics.json says identical, agreement 1, F1 1,
//    pose difference 0;
//  * with a shorter sonar valid distance and a coarser grid the map changes measurably (cell
//    agreement and occupied F1 below 0.95) while the pose does not;
//  * the encoder + gyro filter, mapping on its estimate, moves the pose and the map a little;
//  * a bad --param is refused with exit status 2.

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "child_process.hpp"
#include "status_line.hpp"

namespace irgs::test {
namespace {

namespace fs = std::filesystem;
using std::chrono::milliseconds;
using std::chrono::seconds;

// col,row -> log-odds text (exact: the files print shortest round-trip doubles).
std::map<std::pair<int, int>, std::string> readGrid(const fs::path& path, std::string& header) {
  std::ifstream in(path);
  std::getline(in, header);
  std::map<std::pair<int, int>, std::string> cells;
  std::string line;
  while (std::getline(in, line)) {
    int col = 0, row = 0, used = 0;
    if (std::sscanf(line.c_str(), "%d,%d,%n", &col, &row, &used) == 2)
      cells[{col, row}] = line.substr(static_cast<std::size_t>(used));
  }
  return cells;
}

struct Pose {
  double t = 0.0, x = 0.0, y = 0.0, theta = 0.0;
};

int runRerun(const std::string& args, const fs::path& log) {
  const std::string command =
      std::string(IRGS_RERUN_EXE) + " " + args + " > " + log.string() + " 2>&1";
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

nlohmann::json readJson(const fs::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

std::string slurp(const fs::path& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

class RerunEndToEnd : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string pattern = (fs::temp_directory_path() / "irgs-rerun-e2e-XXXXXX").string();
    ASSERT_NE(::mkdtemp(pattern.data()), nullptr);
    dir_ = pattern;
    ::setenv("QT_QPA_PLATFORM", "offscreen", 1);
  }
  void TearDown() override {
    if (std::getenv("IRGS_KEEP_TEST_DIR") != nullptr) {
      std::printf("[ info ] kept %s\n", dir_.c_str());
      return;
    }
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  fs::path dir_;
};

TEST_F(RerunEndToEnd, DefaultsReproduceTheLiveSessionAndChangedParametersChangeTheMap) {
  const fs::path recording = dir_ / "live.irgsrec";
  {
    const std::string link = (dir_ / "robot").string();
    ChildProcess robot({IRGS_ROBOT_EXE, "--link", link, "--baud", "115200", "--seed", "5"});
    const auto pts = robot.readLine(Clock::now() + seconds(30));
    ASSERT_TRUE(pts && pts->rfind("/dev/pts/", 0) == 0) << "irgs-robot printed no pty path";
    ChildProcess gui({IRGS_GUI_EXE, "--settings", (dir_ / "live.ini").string(), "--map",
                      std::string(IRGS_SOURCE_DIR) + "/resources/maps/default.json",
                      "--window-size", "1000x700", "--control-stdin", "--status-interval", "0.2",
                      "--connect", "serial://" + link + "?baud=115200", "--record",
                      recording.string(), "--trajectory-out", (dir_ / "live.csv").string(),
                      "--grid-out", (dir_ / "live_grid.csv").string()});
    waitStatus(
        gui, [](const Fields& f) { return f.count("link") && f.at("link") == "connected"; }, 60.0,
        "the link to come up");
    const double start = number(
        waitStatus(
            gui, [](const Fields& f) { return number(f, "samples") >= 20; }, 30.0, "telemetry"),
        "samples");
    gui.writeLine("drive 0.25 0.35");
    waitStatus(
        gui, [&](const Fields& f) { return number(f, "samples") >= start + 100; }, 30.0,
        "5 s of driving");
    gui.writeLine("stop");
    waitStatus(
        gui, [](const Fields& f) { return std::abs(number(f, "v")) < 1e-3; }, 30.0,
        "the robot to stop");
    gui.writeLine("quit");
    ASSERT_TRUE(waitExit(gui, 30.0)) << "irgs did not quit";
  }
  ASSERT_TRUE(fs::exists(recording));

  // ---- the recorded parameters ----
  const fs::path same = dir_ / "same";
  ASSERT_EQ(runRerun(recording.string() + " --out " + same.string(), dir_ / "same.log"), 0)
      << slurp(dir_ / "same.log");
  const nlohmann::json m = readJson(same / "metrics.json");
  EXPECT_TRUE(m["grid"]["identical"].get<bool>());
  EXPECT_EQ(m["grid"]["agreement"].get<double>(), 1.0);
  EXPECT_EQ(m["grid"]["occupied"]["f1"].get<double>(), 1.0);
  EXPECT_EQ(m["pose"]["max_position_m"].get<double>(), 0.0);
  EXPECT_EQ(m["changed_parameters"].size(), 0u);
  EXPECT_EQ(m["recorded"]["parameters"]["grid_resolution_m"], "0.01");  // from the meta
  for (const char* file : {"recorded_map.png", "rerun_map.png", "recorded_map.yaml",
                           "recorded_trajectory.csv", "rerun_trajectory.csv"})
    EXPECT_TRUE(fs::exists(same / file)) << file;

  // The same map as the live session showed, cell for cell, bit for bit.
  std::string live_header, rerun_header;
  const auto live_grid = readGrid(dir_ / "live_grid.csv", live_header);
  const auto rerun_grid = readGrid(same / "recorded_grid.csv", rerun_header);
  ASSERT_GE(live_grid.size(), 1000u) << "the live run mapped almost nothing";
  EXPECT_EQ(live_header, rerun_header);
  std::size_t differing = 0;
  for (const auto& [cell, value] : live_grid) {
    const auto it = rerun_grid.find(cell);
    differing += (it == rerun_grid.end() || it->second != value) ? 1 : 0;
  }
  EXPECT_EQ(differing, 0u) << "of " << live_grid.size() << " live cells";
  EXPECT_EQ(rerun_grid.size(), live_grid.size());

  // Every live pose at its robot time.
  std::vector<Pose> live;
  {
    std::ifstream in(dir_ / "live.csv");
    std::string line;
    std::getline(in, line);
    while (std::getline(in, line)) {
      Pose p;
      if (std::sscanf(line.c_str(), "%lf,%lf,%lf,%lf", &p.t, &p.x, &p.y, &p.theta) == 4)
        live.push_back(p);
    }
  }
  // By robot time in microseconds since the first sample: the session's clock of a linked robot
  // (MavlinkRemoteRobot) starts at its first sample, which is what --trajectory-out writes.
  std::map<long long, Pose> rerun_poses;
  {
    std::ifstream in(same / "recorded_trajectory.csv");
    std::string line;
    std::getline(in, line);
    std::optional<double> first;
    while (std::getline(in, line)) {
      double t_rec = 0.0;
      Pose p;
      if (std::sscanf(line.c_str(), "%lf,%lf,%lf,%lf,%lf", &t_rec, &p.t, &p.x, &p.y, &p.theta) != 5)
        continue;
      if (!first)
        first = p.t;
      rerun_poses[std::llround((p.t - *first) * 1e6)] = p;
    }
  }
  ASSERT_GE(live.size(), 50u);
  std::size_t found = 0;
  double max_error = 0.0;
  for (const Pose& p : live) {
    const auto it = rerun_poses.find(std::llround(p.t * 1e6));
    if (it == rerun_poses.end())
      continue;
    ++found;
    max_error = std::max(max_error, std::hypot(p.x - it->second.x, p.y - it->second.y));
  }
  EXPECT_EQ(found, live.size()) << "live poses missing from the re-run";
  EXPECT_LT(max_error, 1e-6);  // the CSV prints 9 significant digits

  // ---- changed parameters ----
  const fs::path changed = dir_ / "changed";
  ASSERT_EQ(runRerun(recording.string() +
                         " --param sonar_valid_distance_m=0.8 --param grid_resolution_m=0.02"
                         " --out " +
                         changed.string(),
                     dir_ / "changed.log"),
            0)
      << slurp(dir_ / "changed.log");
  const nlohmann::json c = readJson(changed / "metrics.json");
  EXPECT_FALSE(c["grid"]["identical"].get<bool>());
  EXPECT_EQ(c["grid"]["resolution_m"].get<double>(), 0.02);
  EXPECT_LT(c["grid"]["agreement"].get<double>(), 0.95);
  EXPECT_LT(c["grid"]["occupied"]["f1"].get<double>(), 0.95);
  EXPECT_EQ(c["pose"]["max_position_m"].get<double>(), 0.0);
  EXPECT_EQ(c["changed_parameters"].size(), 2u);
  std::printf("[ info ] %zu live cells reproduced; changed: %s", live_grid.size(),
              slurp(dir_ / "changed.log").c_str());

  // An estimator on the recorded ticks and gyro, mapping on its estimate: the pose moves a
  // little (the 001 filter is not the robot's own odometry), the map with it.
  const fs::path filtered = dir_ / "filtered";
  ASSERT_EQ(runRerun(recording.string() +
                         " --param estimator=encoder-gyro --param map_on_estimate=1 --out " +
                         filtered.string(),
                     dir_ / "filtered.log"),
            0)
      << slurp(dir_ / "filtered.log");
  const nlohmann::json f = readJson(filtered / "metrics.json");
  EXPECT_EQ(f["rerun"]["parameters"]["estimator"], "encoder-gyro");
  EXPECT_GT(f["pose"]["rms_position_m"].get<double>(), 1e-4);
  EXPECT_LT(f["pose"]["max_position_m"].get<double>(), 0.2);
  EXPECT_FALSE(f["grid"]["identical"].get<bool>());
  std::printf("[ info ] filtered: %s", slurp(dir_ / "filtered.log").c_str());

  EXPECT_EQ(runRerun(recording.string() + " --param grid_resolution_m=fine --out " +
                         (dir_ / "bad").string(),
                     dir_ / "bad.log"),
            2);
  EXPECT_NE(slurp(dir_ / "bad.log").find("not a number"), std::string::npos);
}

}  // namespace
}  // namespace irgs::test
