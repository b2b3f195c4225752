// The session's one ActivityRunner (app/gui/activity_runner.hpp) with a real simulated robot,
// ticked by hand: one activity drives the robot at a time, a second start is refused or
// preempts it with a console line that says which, STOP and a new robot end it, a drive script
// outlives a reset; and the kinds of activity on literal samples: a behaviour's paused clock,
// a host mission starting primitives on a robot with MotionControl and hearing its reports.

#include "app/gui/activity_runner.hpp"

#include <gtest/gtest.h>

#include <QSignalSpy>
#include <QStringList>
#include <deque>
#include <memory>
#include <vector>

#include "app/gui/behaviour_activity.hpp"
#include "app/gui/behaviour_controller.hpp"
#include "app/gui/drive_script_player.hpp"
#include "app/gui/mission_activity.hpp"
#include "app/gui/session_controller.hpp"
#include "tests/e2e/app_test_support.hpp"

namespace irgs::gui {
namespace {

// Drives at a constant velocity and counts the samples it saw; finishes after `samples` of them
// (0: never).
class CountingBehaviour final : public Behaviour {
 public:
  explicit CountingBehaviour(VelocityCommand command, int samples = 0)
      : command_(command), limit_(samples) {}
  VelocityCommand onSample(const TelemetrySample& sample) override {
    times_.push_back(sample.time_s);
    return command_;
  }
  BehaviourStatus status() const override {
    BehaviourStatus s;
    s.finished = limit_ > 0 && static_cast<int>(times_.size()) >= limit_;
    s.message = s.finished ? "counted" : "";
    return s;
  }
  std::string_view name() const override { return "counting"; }
  const std::vector<double>& times() const { return times_; }

 private:
  VelocityCommand command_;
  int limit_ = 0;
  std::vector<double> times_;
};

class ActivityRunnerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    test::ensureApp();
    session_ = std::make_unique<SessionController>(test::thesisRobot(), test::simulatedFactory());
    QObject::connect(session_.get(), &SessionController::consoleEvent,
                     [this](EventLevel, double, const QString& text) { console_ << text; });
    session_->loadWorld(test::squareRoom(), QStringLiteral("room.json"));
  }
  void run(double seconds) {
    for (int i = 0; i < static_cast<int>(seconds / 0.02 + 0.5); ++i)
      session_->tick(0.02);
  }
  ActivityRunner& runner() { return session_->runner(); }
  ActivityRunner::Id start(std::shared_ptr<Behaviour> b, const QString& label,
                           ActivityRunner::Policy policy) {
    return runner().start(std::make_unique<BehaviourActivity>(std::move(b)), label, policy);
  }

  std::unique_ptr<SessionController> session_;
  QStringList console_;
};

TEST_F(ActivityRunnerTest, ASecondStartIsRefusedWhileOneRunsAndTheFirstKeepsTheRobot) {
  auto forward = std::make_shared<CountingBehaviour>(VelocityCommand{0.1, 0.0});
  auto turn = std::make_shared<CountingBehaviour>(VelocityCommand{0.0, 0.5});
  const ActivityRunner::Id first =
      start(forward, QStringLiteral("Forward"), ActivityRunner::Policy::kRefuseIfBusy);
  ASSERT_NE(first, 0u);
  run(0.5);
  EXPECT_EQ(start(turn, QStringLiteral("Turn"), ActivityRunner::Policy::kRefuseIfBusy), 0u);
  EXPECT_TRUE(console_.contains(
      QStringLiteral("Turn refused: Forward is driving the robot; stop it first")))
      << console_.join(QLatin1Char('\n')).toStdString();
  const std::size_t seen = forward->times().size();
  run(0.5);
  EXPECT_EQ(runner().current(), first);
  EXPECT_GT(forward->times().size(), seen + 40);  // it still gets every sample (100 Hz)
  EXPECT_TRUE(turn->times().empty());
  EXPECT_DOUBLE_EQ(session_->command().linear_mps, 0.1);
  EXPECT_DOUBLE_EQ(session_->command().angular_radps, 0.0);
}

TEST_F(ActivityRunnerTest, APreemptingStartEndsTheRunningOneAndSaysSo) {
  auto forward = std::make_shared<CountingBehaviour>(VelocityCommand{0.1, 0.0});
  auto turn = std::make_shared<CountingBehaviour>(VelocityCommand{0.0, 0.5});
  QSignalSpy finished(&runner(), &ActivityRunner::finished);
  const ActivityRunner::Id first =
      start(forward, QStringLiteral("Forward"), ActivityRunner::Policy::kRefuseIfBusy);
  run(0.3);
  const ActivityRunner::Id second =
      start(turn, QStringLiteral("Turn"), ActivityRunner::Policy::kPreempt);
  ASSERT_NE(second, 0u);
  EXPECT_TRUE(console_.contains(QStringLiteral("Forward preempted by Turn")));
  ASSERT_EQ(finished.count(), 1);
  EXPECT_EQ(finished[0][0].value<ActivityRunner::Id>(), first);
  EXPECT_TRUE(finished[0][1].toBool());
  EXPECT_EQ(finished[0][2].toString(), QStringLiteral("Forward aborted: preempted by Turn"));
  const std::size_t forward_seen = forward->times().size();
  run(0.3);
  EXPECT_EQ(forward->times().size(), forward_seen);
  EXPECT_FALSE(turn->times().empty());
  EXPECT_DOUBLE_EQ(session_->command().angular_radps, 0.5);
}

TEST_F(ActivityRunnerTest, TwoControllersShareTheRunnerAndSeeOnlyTheirOwnBehaviour) {
  // Planning and navigation each have a BehaviourController; today's bug was that the last one
  // to install the session's hooks silently took the robot.
  BehaviourController planning(*session_);
  BehaviourController navigation(*session_);
  QSignalSpy planning_samples(&planning, &BehaviourController::sampleConsumed);
  QSignalSpy navigation_samples(&navigation, &BehaviourController::sampleConsumed);
  QSignalSpy navigation_finished(&navigation, &BehaviourController::finished);
  ASSERT_TRUE(planning.start(std::make_shared<CountingBehaviour>(VelocityCommand{0.1, 0.0}),
                             QStringLiteral("Map building")));
  EXPECT_FALSE(navigation.start(std::make_shared<CountingBehaviour>(VelocityCommand{0.0, 0.3}),
                                QStringLiteral("delivery A → B")));
  EXPECT_TRUE(console_.contains(
      QStringLiteral("delivery A → B refused: Map building is driving the robot; stop it first")));
  run(0.3);
  EXPECT_TRUE(planning.running());
  EXPECT_FALSE(navigation.running());
  EXPECT_GT(planning_samples.count(), 20);
  EXPECT_EQ(navigation_samples.count(), 0);
  EXPECT_EQ(navigation_finished.count(), 0);  // refused is not finished: it never started
}

TEST_F(ActivityRunnerTest, StopEndsTheActivityAndStopsTheRobot) {
  BehaviourController planning(*session_);
  QSignalSpy finished(&planning, &BehaviourController::finished);
  ASSERT_TRUE(planning.start(std::make_shared<CountingBehaviour>(VelocityCommand{0.2, 0.0}),
                             QStringLiteral("Goal")));
  run(0.5);
  EXPECT_DOUBLE_EQ(session_->command().linear_mps, 0.2);
  runner().stop(QStringLiteral("STOP pressed"));
  EXPECT_FALSE(runner().busy());
  EXPECT_FALSE(planning.running());
  ASSERT_EQ(finished.count(), 1);
  EXPECT_EQ(finished[0][1].toString(), QStringLiteral("Goal aborted: STOP pressed"));
  run(0.5);
  EXPECT_DOUBLE_EQ(session_->command().linear_mps, 0.0);
  EXPECT_NEAR(session_->latestSample()->measured_velocity.linear_mps, 0.0, 1e-6);
}

TEST_F(ActivityRunnerTest, ABehaviourThatFinishesStopsTheRobotAndTheUserDrivesAgain) {
  BehaviourController planning(*session_);
  QSignalSpy finished(&planning, &BehaviourController::finished);
  ASSERT_TRUE(planning.start(std::make_shared<CountingBehaviour>(VelocityCommand{0.2, 0.0}, 30),
                             QStringLiteral("Goal")));
  run(1.0);
  ASSERT_EQ(finished.count(), 1);
  EXPECT_FALSE(finished[0][0].toBool());
  EXPECT_EQ(finished[0][1].toString(), QStringLiteral("counted"));
  EXPECT_FALSE(runner().busy());
  EXPECT_DOUBLE_EQ(session_->command().linear_mps, 0.0);
  // The user drives again: nothing takes the robot back.
  session_->drive(0.1, 0.0);
  run(0.3);
  EXPECT_DOUBLE_EQ(session_->command().linear_mps, 0.1);
}

TEST_F(ActivityRunnerTest, ANewRobotEndsABehaviourButADriveScriptCarriesOn) {
  BehaviourController planning(*session_);
  QSignalSpy finished(&planning, &BehaviourController::finished);
  ASSERT_TRUE(planning.start(std::make_shared<CountingBehaviour>(VelocityCommand{0.2, 0.0}),
                             QStringLiteral("Goal")));
  run(0.2);
  session_->resetRobotToStart();
  ASSERT_EQ(finished.count(), 1);
  EXPECT_EQ(finished[0][1].toString(), QStringLiteral("Goal aborted: the robot was replaced"));

  DriveScriptPlayer player(*session_, DriveScript({{0.0, {0.15, 0.0}}, {100.0, {0.0, 0.0}}}));
  ASSERT_TRUE(player.start());
  run(0.3);
  session_->resetRobotToStart();
  EXPECT_EQ(runner().label(), QStringLiteral("Drive script"));
  run(0.5);  // the new robot drives the script's command
  EXPECT_GT(session_->latestSample()->measured_velocity.linear_mps, 0.1);
}

TEST(BehaviourActivity, HidesThePausedStretchFromTheBehavioursClock) {
  auto behaviour = std::make_shared<CountingBehaviour>(VelocityCommand{0.1, 0.0});
  BehaviourActivity activity(behaviour);
  TelemetrySample s;
  s.time_s = 1.0;
  activity.onSample(s);
  activity.setPaused(true, 1.0);
  activity.setPaused(false, 4.0);  // 3 s paused
  s.time_s = 4.01;
  activity.onSample(s);
  ASSERT_EQ(behaviour->times().size(), 2u);
  EXPECT_NEAR(behaviour->times()[1], 1.01, 1e-12);
  // Its answer holds one robot step (learnt from the samples' spacing) at a time.
  s.time_s = 4.02;
  activity.onSample(s);
  const ActivityCommand command = activity.command(4.02);
  ASSERT_TRUE(command.velocity.has_value());
  EXPECT_DOUBLE_EQ(command.velocity->linear_mps, 0.1);
  EXPECT_NEAR(command.next_change_s, 4.03, 1e-9);
}

// A robot with motion primitives: a sample every 0.1 s of the time it is given (stamped 0, 0.1,
// ...), and the reports the test queues, handed out once a sample has reached their time (as
// MotionControl promises).
class PrimitiveRobot final : public Robot, public MotionControl {
 public:
  PrimitiveRobot(RobotProfile profile, bool has_primitives)
      : profile_(std::move(profile)), has_primitives_(has_primitives) {}
  const RobotProfile& profile() const override { return profile_; }
  std::string describe() const override { return "robot with primitives"; }
  void drive(const VelocityCommand& command) override { drives.push_back(command); }
  void stop() override { drives.push_back({}); }
  std::vector<TelemetrySample> update(double wall_elapsed_s) override {
    std::vector<TelemetrySample> out;
    owed_s_ += wall_elapsed_s;
    while (owed_s_ >= 0.1 - 1e-9) {
      owed_s_ -= 0.1;
      TelemetrySample s;
      s.time_s = next_s_;
      last_s_ = next_s_;
      next_s_ += 0.1;
      out.push_back(s);
    }
    return out;
  }
  MotionControl* motionControl() override { return has_primitives_ ? this : nullptr; }
  bool supports(motion::PrimitiveKind) const override { return true; }
  void start(const motion::Primitive& primitive) override { started.push_back(primitive); }
  void cancel() override { ++cancels; }
  std::vector<motion::MotionReport> takeReports() override {
    std::vector<motion::MotionReport> due;
    while (!queued.empty() && queued.front().time_s <= last_s_) {
      due.push_back(queued.front());
      queued.pop_front();
    }
    return due;
  }

  std::vector<VelocityCommand> drives;
  std::vector<motion::Primitive> started;
  int cancels = 0;
  std::deque<motion::MotionReport> queued;

 private:
  RobotProfile profile_;
  bool has_primitives_ = true;
  double owed_s_ = 0.0;
  double next_s_ = 0.0;
  double last_s_ = -1.0;  // time of the newest sample handed out
};

// Drives 1 m as a primitive, then holds a slow turn on the host until 2 more samples passed;
// records what it heard, in order.
class DriveThenTurnMission final : public Mission {
 public:
  void onSample(const TelemetrySample& sample) override {
    heard.push_back("sample " + std::to_string(sample.time_s));
    if (!asked_) {
      asked_ = true;
      request_ = StartPrimitive{{7, motion::DriveSpec{1.0}}};
    } else if (done_ && ++after_done_ == 1) {
      request_ = HoldVelocity{{0.0, 0.2}};
    }
  }
  void onReport(const motion::MotionReport& report) override {
    heard.push_back(std::string("report ") + motion::toString(report.kind) + " " +
                    std::to_string(report.time_s));
    done_ |= report.kind == motion::ReportKind::kDone;
  }
  std::optional<MissionRequest> takeRequest() override { return std::exchange(request_, {}); }
  BehaviourStatus status() const override {
    BehaviourStatus s;
    s.finished = after_done_ >= 3;
    s.message = "drove and turned";
    return s;
  }
  std::string_view name() const override { return "drive then turn"; }

  std::vector<std::string> heard;

 private:
  bool asked_ = false;
  bool done_ = false;
  int after_done_ = 0;
  std::optional<MissionRequest> request_;
};

TEST(MissionActivity, StartsThePrimitivesItsMissionAsksForAndHearsTheReportsInTimeOrder) {
  test::ensureApp();
  PrimitiveRobot* robot = nullptr;
  SessionController session(test::thesisRobot(),
                            [&robot](const WorldMap&, const RobotProfile& profile) {
                              auto made = std::make_unique<PrimitiveRobot>(profile, true);
                              robot = made.get();
                              return std::unique_ptr<Robot>(std::move(made));
                            });
  session.loadWorld(test::squareRoom(), QStringLiteral("room.json"));
  auto mission = std::make_shared<DriveThenTurnMission>();
  QSignalSpy finished(&session.runner(), &ActivityRunner::finished);
  ASSERT_NE(session.runner().start(std::make_unique<MissionActivity>(mission),
                                   QStringLiteral("Drive then turn"),
                                   ActivityRunner::Policy::kRefuseIfBusy),
            0u);
  session.tick(0.1);  // sample at 0.0: the mission asks for the drive
  ASSERT_EQ(robot->started.size(), 1u);
  EXPECT_EQ(robot->started[0].id, 7);
  // While the primitive runs the host leaves the wheels alone.
  const std::size_t drives = robot->drives.size();
  motion::MotionReport started;
  started.id = 7;
  started.kind = motion::ReportKind::kStarted;
  started.time_s = 0.05;
  motion::MotionReport done = started;
  done.kind = motion::ReportKind::kDone;
  done.time_s = 0.15;
  robot->queued = {started, done};
  for (int i = 0; i < 6; ++i)
    session.tick(0.1);
  const std::vector<std::string> in_time_order = {"sample 0.000000", "report started 0.050000",
                                                  "sample 0.100000", "report done 0.150000",
                                                  "sample 0.200000"};
  ASSERT_GE(mission->heard.size(), in_time_order.size());
  EXPECT_EQ(std::vector<std::string>(mission->heard.begin(), mission->heard.begin() + 5),
            in_time_order);
  // After kDone it holds a turn on the host, then finishes and stops the robot.
  ASSERT_GT(robot->drives.size(), drives);
  EXPECT_EQ(robot->drives[drives].angular_radps, 0.2);
  ASSERT_EQ(finished.count(), 1);
  EXPECT_FALSE(finished[0][1].toBool());
  EXPECT_EQ(robot->drives.back(), VelocityCommand{});
  EXPECT_EQ(robot->cancels, 0);
}

TEST(MissionActivity, IsRefusedOnARobotThatRunsNoPrimitivesAndAStopCancelsThePrimitive) {
  test::ensureApp();
  SessionController plain(test::thesisRobot(), [](const WorldMap&, const RobotProfile& profile) {
    return std::unique_ptr<Robot>(std::make_unique<PrimitiveRobot>(profile, false));
  });
  plain.loadWorld(test::squareRoom(), QStringLiteral("room.json"));
  QStringList console;
  QObject::connect(&plain, &SessionController::consoleEvent,
                   [&console](EventLevel, double, const QString& text) { console << text; });
  EXPECT_EQ(plain.runner().start(
                std::make_unique<MissionActivity>(std::make_shared<DriveThenTurnMission>()),
                QStringLiteral("Drive then turn"), ActivityRunner::Policy::kRefuseIfBusy),
            0u);
  EXPECT_TRUE(console.contains(QStringLiteral(
      "Drive then turn refused: drive then turn needs a robot that runs motion primitives")))
      << console.join(QLatin1Char('\n')).toStdString();
  EXPECT_FALSE(plain.runner().busy());

  PrimitiveRobot* robot = nullptr;
  SessionController session(test::thesisRobot(),
                            [&robot](const WorldMap&, const RobotProfile& profile) {
                              auto made = std::make_unique<PrimitiveRobot>(profile, true);
                              robot = made.get();
                              return std::unique_ptr<Robot>(std::move(made));
                            });
  session.loadWorld(test::squareRoom(), QStringLiteral("room.json"));
  ASSERT_NE(session.runner().start(
                std::make_unique<MissionActivity>(std::make_shared<DriveThenTurnMission>()),
                QStringLiteral("Drive then turn"), ActivityRunner::Policy::kRefuseIfBusy),
            0u);
  session.tick(0.1);
  ASSERT_EQ(robot->started.size(), 1u);
  session.runner().stop(QStringLiteral("STOP pressed"));
  EXPECT_EQ(robot->cancels, 1);
  EXPECT_EQ(robot->drives.back(), VelocityCommand{});
}

}  // namespace
}  // namespace irgs::gui
