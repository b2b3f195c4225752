// SessionController with a real simulated robot, ticked by hand (no timers, no sleeps).

#include "app/gui/session_controller.hpp"

#include <gtest/gtest.h>

#include <QSignalSpy>
#include <QStringList>

#include "app/gui/drive_script_player.hpp"
#include "core/scenario/scenario_runner.hpp"
#include "tests/e2e/app_test_support.hpp"

namespace irgs::gui {
namespace {

struct Recorded {
  EventLevel level;
  QString text;
};

class SessionControllerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    test::ensureApp();
    session_ = std::make_unique<SessionController>(test::thesisRobot(), test::simulatedFactory());
    QObject::connect(session_.get(), &SessionController::consoleEvent,
                     [this](EventLevel level, double, const QString& text) {
                       events_.push_back({level, text});
                     });
    session_->loadWorld(test::squareRoom(), QStringLiteral("room.json"));
  }

  // Advances the session by `seconds` of wall time in 20 ms ticks (speed 1: simulated time too).
  void run(double seconds) {
    for (int i = 0; i < static_cast<int>(seconds / 0.02 + 0.5); ++i)
      session_->tick(0.02);
  }

  bool sawEvent(const QString& fragment) const {
    for (const Recorded& e : events_) {
      if (e.text.contains(fragment, Qt::CaseInsensitive))
        return true;
    }
    return false;
  }

  std::unique_ptr<SessionController> session_;
  std::vector<Recorded> events_;
};

TEST_F(SessionControllerTest, LoadingAWorldPutsTheRobotAtTheStartAndReportsIt) {
  ASSERT_TRUE(session_->latestSample().has_value());
  EXPECT_DOUBLE_EQ(session_->latestSample()->odometry_pose.x, 0.0);
  EXPECT_TRUE(sawEvent(QStringLiteral("Map 'test room' (room.json)")));
  EXPECT_NE(session_->simulationControl(), nullptr);
}

TEST_F(SessionControllerTest, DrivingForwardMovesTheRobotAndAdvancesTime) {
  session_->drive(0.2, 0.0);
  run(2.0);
  ASSERT_TRUE(session_->latestSample().has_value());
  EXPECT_GT(session_->latestSample()->odometry_pose.x, 0.2);
  EXPECT_NEAR(session_->displayTime_s(), 2.0, 0.05);
}

TEST_F(SessionControllerTest, SonarSamplesFillTheOccupancyGrid) {
  QSignalSpy grid_changed(session_.get(), &SessionController::gridChanged);
  run(1.0);
  EXPECT_GT(session_->grid().exploredArea_m2(), 0.5);
  EXPECT_GT(grid_changed.count(), 10);
}

TEST_F(SessionControllerTest, PausedSimulationDoesNotAdvanceUntilStepped) {
  session_->setPaused(true);
  const double before = session_->displayTime_s();
  run(1.0);
  EXPECT_DOUBLE_EQ(session_->displayTime_s(), before);
  session_->singleStep();
  EXPECT_GT(session_->displayTime_s(), before);
  EXPECT_LT(session_->displayTime_s(), before + 0.1);
  EXPECT_TRUE(sawEvent(QStringLiteral("Simulation paused")));
}

TEST_F(SessionControllerTest, DrivingIntoAWallReportsTheCollision) {
  session_->drive(0.3, 0.0);
  run(12.0);
  EXPECT_TRUE(sawEvent(QStringLiteral("Collision")));
  EXPECT_TRUE(sawEvent(QStringLiteral("pressed")));
  EXPECT_LT(session_->latestSample()->true_pose->x, 1.5);
}

TEST_F(SessionControllerTest, ResetRobotReturnsToStartAndKeepsTimeMonotonic) {
  session_->drive(0.2, 0.5);
  run(2.0);
  const double before = session_->displayTime_s();
  session_->resetRobotToStart();
  EXPECT_DOUBLE_EQ(session_->latestSample()->odometry_pose.x, 0.0);
  EXPECT_DOUBLE_EQ(session_->latestSample()->odometry_pose.y, 0.0);
  run(0.5);
  EXPECT_GT(session_->displayTime_s(), before);
}

TEST_F(SessionControllerTest, MaxSpeedKeepsEachTickWithinItsBudget) {
  session_->setSpeedFactor(0.0);
  session_->drive(0.2, 0.3);
  QElapsedTimer clock;
  for (int i = 0; i < 30; ++i) {
    clock.start();
    session_->tick(0.016);
    // The budget is ~8 ms of grid work plus the simulator's own; the bound is generous for
    // sanitizer builds on a loaded machine and only catches a frozen GUI.
    EXPECT_LT(clock.elapsed(), 250) << "tick " << i;
  }
  EXPECT_GT(session_->displayTime_s(), 0.5);
}

TEST_F(SessionControllerTest, SensorLinesAreRateLimitedByWallTime) {
  QElapsedTimer wall;
  wall.start();
  run(3.0);
  const double wall_s = static_cast<double>(wall.elapsed()) / 1000.0;
  int sensor_lines = 0;
  QString last;
  for (const Recorded& e : events_) {
    if (e.level == EventLevel::kSensor) {
      ++sensor_lines;
      last = e.text;
    }
  }
  // The first pair (pose, sonar) is immediate, then at most one pair per kSensorLinePeriod_s of
  // wall time.
  EXPECT_GE(sensor_lines, 2);
  EXPECT_LE(sensor_lines,
            2 * (1 + static_cast<int>(wall_s / SessionController::kSensorLinePeriod_s)));
  EXPECT_TRUE(last.contains(QStringLiteral("sonar cm"))) << last.toStdString();
}

// The GUI path (session + drive-script player, ticked at irregular wall intervals) and the
// headless scenario runner step the same simulator with the same commands at the same steps.
TEST(SessionControllerScript, ScriptedDriveMatchesTheHeadlessRunnerWhateverTheTickPattern) {
  test::ensureApp();
  const char* text =
      "0.0 drive 0.0 90\n"
      "1.5 drive 0.25 0\n"
      "2.25 drive 0.2 -40\n"
      "3.0 stop\n";
  const DriveScriptResult parsed = parseDriveScript(text, "test script");
  ASSERT_TRUE(parsed.script.has_value());
  const WorldMap room = test::squareRoom();
  const RobotProfile profile = test::thesisRobot();

  std::vector<Pose2> finals;
  std::vector<double> times;
  for (const int pattern : {0, 1, 2}) {
    SessionController session(profile, test::simulatedFactory(11));
    session.loadWorld(room, QStringLiteral("room.json"));
    session.setSpeedFactor(pattern == 2 ? 2.0 : 1.0);
    DriveScriptPlayer player(session, *parsed.script);
    player.start();
    std::uint32_t lcg = 12345;
    while (session.robotTime_s() < 3.5) {
      double wall_s = 0.016;
      if (pattern == 1) {  // irregular frames between 2 and 50 ms
        lcg = lcg * 1664525u + 1013904223u;
        wall_s = 0.002 + 0.048 * static_cast<double>(lcg >> 8) / static_cast<double>(1u << 24);
      }
      session.tick(wall_s);
    }
    while (session.pendingSamples() > 0)
      session.tick(0.0);
    EXPECT_TRUE(player.finished());
    finals.push_back(*session.latestSample()->true_pose);
    times.push_back(session.latestSample()->time_s);
  }

  for (std::size_t i = 0; i < finals.size(); ++i) {
    ScenarioSpec spec;
    spec.map = room;
    spec.profile = profile;
    spec.script = *parsed.script;
    spec.sim.seed = 11;
    spec.duration_s = times[i];
    const ScenarioResult headless = runScenario(spec);
    EXPECT_NEAR(finals[i].x, headless.metrics.final_truth.x, 1e-9) << "pattern " << i;
    EXPECT_NEAR(finals[i].y, headless.metrics.final_truth.y, 1e-9) << "pattern " << i;
    EXPECT_NEAR(finals[i].theta, headless.metrics.final_truth.theta, 1e-9) << "pattern " << i;
  }
  EXPECT_GT(std::hypot(finals[0].x, finals[0].y), 0.2);  // the script did move the robot
}

}  // namespace
}  // namespace irgs::gui
