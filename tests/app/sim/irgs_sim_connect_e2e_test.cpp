// End to end: `irgs-sim --connect serial://PATH` against the irgs-robot executable on a pty at
// 115200 baud, over MAVLink and over ARCOS (?protocol=arcos, irgs-robot --protocol arcos as a
// P3-DX). irgs-robot makes a symlink PATH to its pty (--link); irgs-sim drives a short script on
// it and writes the usual outputs. Every wait has a deadline; children are always
// reaped.

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "tests/app/sim/child_process.hpp"

namespace {

namespace fs = std::filesystem;
using irgs::test::Child;

std::string readFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Occupied cells (value 0) of a ROS map_server trinary PGM (P5, maxval 255).
long occupiedCells(const fs::path& pgm) {
  std::ifstream in(pgm, std::ios::binary);
  std::string magic;
  int w = 0, h = 0, maxval = 0;
  in >> magic >> std::ws;
  while (in.peek() == '#') {  // comment lines
    std::string comment;
    std::getline(in, comment);
  }
  in >> w >> h >> maxval;
  in.get();
  if (magic != "P5" || w <= 0 || h <= 0 || maxval != 255)
    return -1;
  std::vector<char> pixels(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
  in.read(pixels.data(), static_cast<std::streamsize>(pixels.size()));
  if (!in)
    return -1;
  long occupied = 0;
  for (char c : pixels)
    occupied += static_cast<unsigned char>(c) == 0 ? 1 : 0;
  return occupied;
}

// Length of the odometry path in trajectory.csv (columns 5, 6 = odom_x_m, odom_y_m).
double pathLength(const fs::path& csv, std::size_t& rows) {
  std::ifstream in(csv);
  std::string line;
  std::getline(in, line);  // header
  double length = 0.0;
  std::optional<std::pair<double, double>> last;
  rows = 0;
  while (std::getline(in, line)) {
    std::vector<double> v;
    std::stringstream s(line);
    std::string cell;
    while (std::getline(s, cell, ','))
      v.push_back(std::stod(cell));
    if (v.size() < 7)
      return -1.0;
    if (last)
      length += std::hypot(v[4] - last->first, v[5] - last->second);
    last = std::make_pair(v[4], v[5]);
    ++rows;
  }
  return length;
}

class IrgsSimConnect : public ::testing::Test {
 protected:
  void SetUp() override {
    work_ = fs::temp_directory_path() /
            ("irgs_sim_connect_" + std::to_string(::getpid()) + "_" +
             ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(work_);
    fs::create_directories(work_);
    link_ = work_ / "robot";
  }
  void TearDown() override { fs::remove_all(work_); }

  std::unique_ptr<Child> startRobot() {
    auto robot = std::make_unique<Child>(
        std::vector<std::string>{IRGS_ROBOT_EXE, "--seed", "4", "--link", link_.string()});
    if (!robot->started() || !robot->waitOutput("/dev/pts/", 20.0))
      return nullptr;
    return robot;
  }
  std::string url() const { return "serial://" + link_.string() + "?baud=115200"; }

  fs::path work_;
  fs::path link_;
};

TEST_F(IrgsSimConnect, DrivesTheLinkedRobotAndWritesTheSameOutputs) {
  auto robot = startRobot();
  ASSERT_NE(robot, nullptr);
  const fs::path script = work_ / "drive.txt";
  std::ofstream(script) << "0 drive 0.25 0\n1.5 drive 0.15 40\n3 stop\n";
  const fs::path out = work_ / "out";
  Child sim({IRGS_SIM_EXE, "--connect", url(), "--script", script.string(), "--out", out.string(),
             "--connect-timeout", "10"});
  ASSERT_TRUE(sim.started());
  ASSERT_EQ(sim.wait(60.0), 0) << sim.output();
  for (const char* name :
       {"grid.pgm", "grid.yaml", "grid.png", "metrics.json", "trajectory.csv", "link.json"})
    EXPECT_TRUE(fs::exists(out / name)) << name;
  EXPECT_GT(occupiedCells(out / "grid.pgm"), 0) << "the sonar grid has no occupied cells";
  std::size_t rows = 0;
  EXPECT_GT(pathLength(out / "trajectory.csv", rows), 0.3);
  EXPECT_GE(rows, 20u);
  const std::string link = readFile(out / "link.json");
  EXPECT_NE(link.find("\"stop_acknowledged\": true"), std::string::npos) << link;
  EXPECT_NE(link.find("not available from a linked robot"), std::string::npos);
  EXPECT_NE(sim.output().find("link up"), std::string::npos) << sim.output();
  EXPECT_EQ(robot->wait(0.0), -1) << "irgs-robot died: " << robot->output();
  robot->signal(SIGTERM);
  EXPECT_EQ(robot->wait(10.0), 0);
}

TEST_F(IrgsSimConnect, DrivesAPioneerOverArcosWhenTheUrlSaysSo) {
  const std::string pioneer = std::string(IRGS_SOURCE_DIR) + "/resources/robots/pioneer_p3dx.json";
  auto robot = std::make_unique<Child>(
      std::vector<std::string>{IRGS_ROBOT_EXE, "--protocol", "arcos", "--robot", pioneer, "--seed",
                               "4", "--link", link_.string()});
  ASSERT_TRUE(robot->started());
  ASSERT_TRUE(robot->waitOutput("/dev/pts/", 20.0)) << robot->output();
  const fs::path script = work_ / "drive.txt";
  std::ofstream(script) << "0 drive 0.25 0\n1.5 drive 0.15 40\n3 stop\n";
  const fs::path out = work_ / "out";
  Child sim({IRGS_SIM_EXE, "--connect", url() + "&protocol=arcos", "--robot", pioneer, "--script",
             script.string(), "--out", out.string(), "--connect-timeout", "10"});
  ASSERT_TRUE(sim.started());
  ASSERT_EQ(sim.wait(60.0), 0) << sim.output();
  EXPECT_GT(occupiedCells(out / "grid.pgm"), 0) << "the sonar grid has no occupied cells";
  std::size_t rows = 0;
  EXPECT_GT(pathLength(out / "trajectory.csv", rows), 0.3);
  EXPECT_GE(rows, 20u);
  const std::string link = readFile(out / "link.json");
  EXPECT_NE(link.find("\"protocol\": \"arcos\""), std::string::npos) << link;
  EXPECT_NE(link.find("irgs-robot"), std::string::npos) << "no robot name from SYNC2: " << link;
  // ARCOS acknowledges nothing: the stop is confirmed by a SIP with the wheels at rest.
  EXPECT_NE(link.find("\"stop_acknowledged\": true"), std::string::npos) << link;
  EXPECT_EQ(robot->wait(0.0), -1) << "irgs-robot died: " << robot->output();
  robot->signal(SIGTERM);
  EXPECT_EQ(robot->wait(10.0), 0);
}

TEST_F(IrgsSimConnect, CtrlCStopsTheRobotAndStillWritesTheOutputs) {
  auto robot = startRobot();
  ASSERT_NE(robot, nullptr);
  const fs::path script = work_ / "long.txt";
  std::ofstream(script) << "0 drive 0.2 0\n60 stop\n";
  const fs::path out = work_ / "out";
  Child sim({IRGS_SIM_EXE, "--connect", url(), "--script", script.string(), "--out", out.string()});
  ASSERT_TRUE(sim.waitOutput("running the script", 20.0)) << sim.output();
  sim.signal(SIGINT);
  EXPECT_EQ(sim.wait(20.0), 130) << sim.output();
  EXPECT_TRUE(fs::exists(out / "metrics.json"));
  const std::string link = readFile(out / "link.json");
  EXPECT_NE(link.find("\"cancelled\": true"), std::string::npos) << link;
  EXPECT_NE(link.find("\"stop_acknowledged\": true"), std::string::npos) << link;
  EXPECT_NE(sim.output().find("IRGS_STOP accepted"), std::string::npos) << sim.output();
}

TEST_F(IrgsSimConnect, ARobotThatNeverAnswersIsAClearErrorWithExitCode3) {
  Child sim({IRGS_SIM_EXE, "--connect", "serial://" + (work_ / "nothing").string(), "--out",
             (work_ / "out").string(), "--connect-timeout", "1"});
  ASSERT_TRUE(sim.started());
  EXPECT_EQ(sim.wait(20.0), 3) << sim.output();
  EXPECT_NE(sim.output().find("no robot heartbeat"), std::string::npos) << sim.output();
  EXPECT_FALSE(fs::exists(work_ / "out" / "metrics.json"));
}

}  // namespace
