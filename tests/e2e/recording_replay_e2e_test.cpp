// Issue 6 acceptance: "A session recorded against irgs-robot and replayed shows the same map and
// trajectory (checked numerically)". Two real processes over a real pty at 115200 baud, as in
// linked_gui_e2e_test: irgs (offscreen, --connect, --control-stdin) drives irgs-robot while
// recording (--record); then a second irgs replays the file (--replay at x4) through the same
// decoder, link session and LinkedRobot path. Both write what they showed at exit
// (--trajectory-out, --grid-out) and the two are compared:
//  * trajectory: every replayed pose whose robot time matches a live pose (the views show a
//    subset of samples that depends on GUI ticks) must be the same sample, to 1e-9 m / rad: the
//    same bytes through the same code give the same numbers. At least 90 % must match.
//  * final pose: within 1 mm (the robot stands still for the last second of both runs).
//  * grid: irgs closes the recording when it quits, but the link may have delivered a sample or
//    two after the session's last tick; those only reinforce cells of a robot standing still. So
//    every cell observed live must be observed in the replay and >= 99 % of the union of
//    observed cells must have the same class (occupied log-odds > 0.4, free < -0.4, else
//    unknown). Typical runs: the same cells, 99.95 % of the same class.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
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

struct Pose {
  double t = 0.0, x = 0.0, y = 0.0, theta = 0.0;
};

std::vector<Pose> readTrajectory(const fs::path& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);  // header
  std::vector<Pose> poses;
  while (std::getline(in, line)) {
    Pose p;
    if (std::sscanf(line.c_str(), "%lf,%lf,%lf,%lf", &p.t, &p.x, &p.y, &p.theta) == 4)
      poses.push_back(p);
  }
  return poses;
}

std::map<std::pair<int, int>, double> readGrid(const fs::path& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);  // resolution
  std::map<std::pair<int, int>, double> cells;
  while (std::getline(in, line)) {
    int col = 0, row = 0;
    double lo = 0.0;
    if (std::sscanf(line.c_str(), "%d,%d,%lf", &col, &row, &lo) == 3)
      cells[{col, row}] = lo;
  }
  return cells;
}

int cellClass(double log_odds) {
  return log_odds > 0.4 ? 1 : (log_odds < -0.4 ? -1 : 0);
}

class RecordingReplayEndToEnd : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string pattern = (fs::temp_directory_path() / "irgs-replay-e2e-XXXXXX").string();
    ASSERT_NE(::mkdtemp(pattern.data()), nullptr);
    dir_ = pattern;
    ::setenv("QT_QPA_PLATFORM", "offscreen", 1);
  }
  void TearDown() override {
    if (std::getenv("IRGS_KEEP_TEST_DIR") != nullptr) {  // for a look at the files by hand
      std::printf("[ info ] kept %s\n", dir_.c_str());
      return;
    }
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }

  std::vector<std::string> guiArgs(const std::string& settings) const {
    return {IRGS_GUI_EXE,
            "--settings",
            (dir_ / settings).string(),
            "--map",
            std::string(IRGS_SOURCE_DIR) + "/resources/maps/default.json",
            "--window-size",
            "1000x700",
            "--control-stdin",
            "--status-interval",
            "0.2"};
  }

  // Reads status lines until `done` holds for one; fails the test at the deadline.
  fs::path dir_;
};

TEST_F(RecordingReplayEndToEnd, AReplayedSessionShowsTheSameTrajectoryAndMapAsTheLiveOne) {
  const fs::path recording = dir_ / "live.irgsrec";
  // ---- live: irgs drives irgs-robot and records ----
  {
    const std::string link = (dir_ / "robot").string();
    ChildProcess robot({IRGS_ROBOT_EXE, "--link", link, "--baud", "115200", "--seed", "3"});
    const auto pts = robot.readLine(Clock::now() + seconds(30));
    ASSERT_TRUE(pts && pts->rfind("/dev/pts/", 0) == 0) << "irgs-robot printed no pty path";

    std::vector<std::string> args = guiArgs("live.ini");
    for (const std::string& a :
         {std::string("--connect"), "serial://" + link + "?baud=115200", std::string("--record"),
          recording.string(), std::string("--trajectory-out"), (dir_ / "live.csv").string(),
          std::string("--grid-out"), (dir_ / "live_grid.csv").string()})
      args.push_back(a);
    ChildProcess gui(args);
    waitStatus(
        gui, [](const Fields& f) { return f.count("link") && f.at("link") == "connected"; }, 60.0,
        "the link to come up");
    const double start = number(
        waitStatus(
            gui, [](const Fields& f) { return number(f, "samples") >= 20; }, 30.0, "telemetry"),
        "samples");
    gui.writeLine("drive 0.25 0.35");
    // 4 s of robot time at 20 Hz.
    waitStatus(
        gui, [&](const Fields& f) { return number(f, "samples") >= start + 80; }, 30.0,
        "4 s of driving");
    gui.writeLine("stop");
    const Fields stopped = waitStatus(
        gui, [](const Fields& f) { return std::abs(number(f, "v")) < 1e-3; }, 30.0,
        "the robot to stop");
    // A second standing still, so both runs end on the same pose.
    waitStatus(
        gui,
        [&](const Fields& f) { return number(f, "samples") >= number(stopped, "samples") + 20; },
        30.0, "1 s standing still");
    gui.writeLine("quit");
    ASSERT_TRUE(waitExit(gui, 30.0)) << "irgs did not quit";
  }
  ASSERT_TRUE(fs::exists(recording));
  ASSERT_TRUE(fs::exists(dir_ / "live.csv"));

  // ---- replay at x4 ----
  {
    std::vector<std::string> args = guiArgs("replay.ini");
    for (const std::string& a :
         {std::string("--replay"), recording.string(), std::string("--replay-speed"),
          std::string("4"), std::string("--trajectory-out"), (dir_ / "replay.csv").string(),
          std::string("--grid-out"), (dir_ / "replay_grid.csv").string()})
      args.push_back(a);
    ChildProcess gui(args);
    const auto deadline = Clock::now() + seconds(60);
    bool finished = false;
    while (auto line = gui.readLine(deadline)) {
      if (line->rfind("console info Replay finished", 0) == 0) {
        finished = true;
        break;
      }
    }
    ASSERT_TRUE(finished) << "the replay never finished";
    gui.writeLine("quit");
    ASSERT_TRUE(waitExit(gui, 30.0)) << "irgs did not quit";
  }

  // ---- trajectory ----
  const std::vector<Pose> live = readTrajectory(dir_ / "live.csv");
  const std::vector<Pose> replay = readTrajectory(dir_ / "replay.csv");
  ASSERT_GE(live.size(), 100u);
  ASSERT_GE(replay.size(), 50u);
  std::size_t matched = 0, comparable = 0;
  double max_error = 0.0;
  for (const Pose& r : replay) {
    if (r.t > live.back().t)
      continue;  // the recording's tail after the live run stopped integrating
    ++comparable;
    const auto it = std::lower_bound(live.begin(), live.end(), r.t - 1e-6,
                                     [](const Pose& p, double t) { return p.t < t; });
    if (it == live.end() || std::abs(it->t - r.t) > 1e-6)
      continue;
    ++matched;
    max_error =
        std::max({max_error, std::hypot(it->x - r.x, it->y - r.y), std::abs(it->theta - r.theta)});
  }
  EXPECT_LE(max_error, 1e-9) << "a replayed sample differs from the live one";
  EXPECT_GE(static_cast<double>(matched), 0.9 * static_cast<double>(comparable))
      << matched << " of " << comparable << " replayed poses found in the live trajectory";
  EXPECT_GT(std::hypot(live.back().x - live.front().x, live.back().y - live.front().y), 0.3)
      << "the robot hardly moved: the comparison would prove little";
  EXPECT_NEAR(replay.back().x, live.back().x, 1e-3);
  EXPECT_NEAR(replay.back().y, live.back().y, 1e-3);
  EXPECT_NEAR(replay.back().theta, live.back().theta, 1e-3);

  // ---- grid ----
  const auto live_grid = readGrid(dir_ / "live_grid.csv");
  const auto replay_grid = readGrid(dir_ / "replay_grid.csv");
  ASSERT_GE(live_grid.size(), 1000u) << "the live run mapped almost nothing";
  std::size_t missing = 0, same = 0, total = 0;
  for (const auto& [cell, lo] : live_grid) {
    const auto it = replay_grid.find(cell);
    if (it == replay_grid.end()) {
      ++missing;
      continue;
    }
    ++total;
    same += cellClass(lo) == cellClass(it->second) ? 1 : 0;
  }
  total += replay_grid.size() - (live_grid.size() - missing);  // cells only the replay saw
  EXPECT_EQ(missing, 0u) << "cells mapped live but not in the replay";
  EXPECT_GE(static_cast<double>(same), 0.99 * static_cast<double>(total))
      << same << " of " << total << " cells agree";
  std::printf(
      "[ info ] trajectory: %zu of %zu replayed poses matched, max error %.3g; grid: %zu "
      "live / %zu replay cells, %zu agree\n",
      matched, comparable, max_error, live_grid.size(), replay_grid.size(), same);
}

}  // namespace
}  // namespace irgs::test
