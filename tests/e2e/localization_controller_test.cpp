// The GUI's localization (LocalizationController): an estimator run beside the simulated robot,
// drawn on the canvas and plotted, with single updates reported on the console and the initial
// pose dragged out on the map. Offscreen.

#include "app/gui/localization_controller.hpp"

#include <gtest/gtest.h>

#include <QAction>
#include <QDockWidget>
#include <QMainWindow>
#include <QMenu>
#include <QtTest/QTest>
#include <cmath>
#include <string>

#include "app/gui/session_controller.hpp"
#include "app_test_support.hpp"
#include "core/robot/robot_profile_file.hpp"
#include "core/world/map_file.hpp"
#include "widgets/canvas/map_canvas.hpp"
#include "widgets/plots/error_plot_panel.hpp"

namespace irgs::gui {
namespace {

WorldMap corridor() {
  const MapLoadResult loaded =
      loadMapFile(std::string(IRGS_SOURCE_DIR) + "/resources/maps/corridor_000_table1.json");
  if (!loaded.map)
    throw std::runtime_error("bundled corridor map does not load");
  return *loaded.map;
}

class LocalizationControllerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    test::ensureApp();
    session_ = std::make_unique<SessionController>(test::thesisRobot(), test::simulatedFactory());
    session_->loadWorld(corridor(), QStringLiteral("corridor.json"));
    window_ = std::make_unique<QMainWindow>();
    canvas_ = new widgets::MapCanvas(window_.get());
    window_->setCentralWidget(canvas_);
    window_->resize(900, 700);
    canvas_->setWorldMap(session_->worldMap());
    controller_ = new LocalizationController(*session_, *canvas_, *window_);
    QObject::connect(session_.get(), &SessionController::consoleEvent,
                     [this](EventLevel, double, const QString& text) { lines_ << text; });
  }
  void run(double seconds) {
    for (double t = 0.0; t < seconds; t += 0.05)
      session_->tick(0.05);
  }

  std::unique_ptr<SessionController> session_;
  std::unique_ptr<QMainWindow> window_;
  widgets::MapCanvas* canvas_ = nullptr;
  LocalizationController* controller_ = nullptr;
  QStringList lines_;
};

TEST_F(LocalizationControllerTest, TheEkfFollowsTheRobotAndTheCanvasAndPlotsShowIt) {
  EXPECT_EQ(controller_->runner(), nullptr);
  EXPECT_TRUE(canvas_->estimatorOverlay().empty());
  controller_->setEstimator(EstimatorKind::kStereoEkf);
  ASSERT_NE(controller_->runner(), nullptr);
  EXPECT_FALSE(controller_->dock().isHidden());
  session_->drive(0.3, 0.0);
  run(10.0);
  const EstimatorRunner& runner = *controller_->runner();
  EXPECT_GT(runner.metrics().readings, 50);
  EXPECT_GT(runner.metrics().acceptedFraction(), 0.5);
  EXPECT_LT(runner.metrics().max_position_error_m, 0.1);
  EXPECT_GT(controller_->plots().points().size(), 50u);
  // true, DR and EKF markers; the EKF one carries its covariance for the ellipse.
  const widgets::EstimatorOverlay& overlay = canvas_->estimatorOverlay();
  ASSERT_EQ(overlay.poses.size(), 3u);
  EXPECT_TRUE(overlay.poses.back().covariance.has_value());
  EXPECT_FALSE(overlay.matches.empty());
  const Pose2 truth = *session_->latestSample()->true_pose;
  EXPECT_LT((overlay.poses.back().pose.position() - truth.position()).norm(), 0.1);
}

TEST_F(LocalizationControllerTest, StepUpdatePausesAndPrintsInnovationGateAndFeature) {
  controller_->setEstimator(EstimatorKind::kStereoEkf);
  session_->drive(0.3, 0.0);
  run(2.0);
  lines_.clear();
  const double before = session_->robotTime_s();
  controller_->stepUpdate();
  EXPECT_TRUE(session_->paused());
  const double advanced = session_->robotTime_s() - before;
  EXPECT_GT(advanced, 0.0);
  EXPECT_LE(advanced, 0.05 + 1e-9);  // at most one 40 ms sonar period of 10 ms steps
  const QString text = lines_.join('\n');
  EXPECT_TRUE(text.contains(QStringLiteral("matched"))) << text.toStdString();
  EXPECT_TRUE(text.contains(QStringLiteral("innovation")));
  EXPECT_TRUE(text.contains(QStringLiteral("vs gate")));
  EXPECT_TRUE(text.contains(QStringLiteral("estimate")));
}

TEST_F(LocalizationControllerTest, DraggingOnTheMapSetsTheInitialPoseAndRestarts) {
  controller_->setEstimator(EstimatorKind::kDeadReckoning);
  window_->show();
  canvas_->setView({2.0, 0.775}, 100.0);
  controller_->armInitialPoseDrag(true);
  const QPointF from = canvas_->worldToWidget({3.0, 0.5});
  const QPointF to = canvas_->worldToWidget({3.0, 1.5});  // drag towards +y: heading 90 deg
  QTest::mousePress(canvas_, Qt::LeftButton, {}, from.toPoint());
  QMouseEvent move(QEvent::MouseMove, to, canvas_->mapToGlobal(to), Qt::NoButton, Qt::LeftButton,
                   Qt::NoModifier);
  QCoreApplication::sendEvent(canvas_, &move);
  EXPECT_TRUE(canvas_->estimatorOverlay().drag_pose.has_value());
  QTest::mouseRelease(canvas_, Qt::LeftButton, {}, to.toPoint());
  ASSERT_TRUE(controller_->initialPose().has_value());
  EXPECT_NEAR(controller_->initialPose()->x, 3.0, 0.02);
  EXPECT_NEAR(controller_->initialPose()->y, 0.5, 0.02);
  EXPECT_NEAR(controller_->initialPose()->theta, kPi / 2, 0.05);
  EXPECT_FALSE(controller_->initialPoseDragArmed());
  ASSERT_NE(controller_->runner(), nullptr);
  EXPECT_NEAR(controller_->runner()->initialEstimate().x, 3.0, 0.02);
  // The robot did not move: the drag only set the estimator's belief.
  EXPECT_NEAR(session_->latestSample()->true_pose->x, 2.0, 1e-9);
}

TEST_F(LocalizationControllerTest, ResettingTheRobotRestartsTheEstimatorAndOffClearsTheMap) {
  controller_->setEstimator(EstimatorKind::kStereoEkf);
  session_->drive(0.3, 0.0);
  run(3.0);
  EXPECT_GT(controller_->plots().points().size(), 10u);
  session_->resetRobotToStart();
  EXPECT_LT(controller_->plots().points().size(), 3u);
  EXPECT_LE(controller_->runner()->metrics().steps, 2);
  controller_->setEstimator(std::nullopt);
  EXPECT_EQ(controller_->runner(), nullptr);
  EXPECT_TRUE(canvas_->estimatorOverlay().empty());
  controller_->stepUpdate();  // nothing to step: a console hint, no crash
  EXPECT_TRUE(lines_.last().contains(QStringLiteral("choose an estimator")));
}

// The optical-mouse estimator (paper 004) on the Type (2,0) profile: the simulated robot reads
// its two floor sensors and the canvas shows truth, encoder DR and the mouse pose; the thesis
// robot has no floor sensors and the controller says so instead of starting.
TEST_F(LocalizationControllerTest, MouseOdometryRunsOnTheMouseProfileAndIsRefusedWithoutIt) {
  controller_->setEstimator(EstimatorKind::kMouseOdometry);
  EXPECT_EQ(controller_->runner(), nullptr);
  EXPECT_TRUE(lines_.join('\n').contains(QStringLiteral("/drive/mouse_sensors")))
      << lines_.join('\n').toStdString();

  const RobotProfileResult mouse = loadRobotProfileFile(std::string(IRGS_SOURCE_DIR) +
                                                        "/resources/robots/mouse_type20_004.json");
  ASSERT_TRUE(mouse.profile.has_value());
  SessionController session(*mouse.profile, test::simulatedFactory());
  session.loadWorld(corridor(), QStringLiteral("corridor.json"));
  auto* controller = new LocalizationController(session, *canvas_, *window_);
  controller->setEstimator(EstimatorKind::kMouseOdometry);
  ASSERT_NE(controller->runner(), nullptr);
  session.drive(0.3, 0.2);
  for (double t = 0.0; t < 10.0; t += 0.05)
    session.tick(0.05);
  const EstimatorRunner& runner = *controller->runner();
  EXPECT_GT(runner.metrics().readings, 100);
  EXPECT_GT(runner.metrics().distance_m, 1.0);
  EXPECT_LT(runner.metrics().max_position_error_m, 0.05);
  const widgets::EstimatorOverlay& overlay = canvas_->estimatorOverlay();
  ASSERT_EQ(overlay.poses.size(), 3u);
  EXPECT_EQ(overlay.poses.back().label, QStringLiteral("mouse"));
  delete controller;
}

// The stereo-sonar EKF on paper 000's own three-caster robot: the simulated robot reports its
// six caster encoders, the estimator predicts with J+ and the adaptive noise and updates with
// the sonar; the thesis robot is refused with the drive type named, and the caster robot
// refuses the wheel-encoder EKF.
TEST_F(LocalizationControllerTest, TheCasterEkfRunsOnTheCasterProfileAndIsRefusedWithoutIt) {
  controller_->setEstimator(EstimatorKind::kStereoEkfCaster);
  EXPECT_EQ(controller_->runner(), nullptr);
  EXPECT_FALSE(controller_->estimator().has_value());
  EXPECT_TRUE(lines_.join('\n').contains(QStringLiteral("three_caster")))
      << lines_.join('\n').toStdString();

  const RobotProfileResult caster =
      loadRobotProfileFile(std::string(IRGS_SOURCE_DIR) + "/resources/robots/caster3_000.json");
  ASSERT_TRUE(caster.profile.has_value());
  SessionController session(*caster.profile, test::simulatedFactory());
  session.loadWorld(corridor(), QStringLiteral("corridor.json"));
  QStringList lines;
  QObject::connect(&session, &SessionController::consoleEvent,
                   [&lines](EventLevel, double, const QString& text) { lines << text; });
  auto* controller = new LocalizationController(session, *canvas_, *window_);
  controller->setEstimator(EstimatorKind::kStereoEkf);
  EXPECT_EQ(controller->runner(), nullptr);
  EXPECT_TRUE(lines.join('\n').contains(QStringLiteral("use 'ekf-caster'")))
      << lines.join('\n').toStdString();
  // The menu offers it (every estimator is listed) and picking it starts it.
  QAction* entry = nullptr;
  for (QAction* a : controller->menu().actions())
    if (a->text() == QString::fromLatin1(displayName(EstimatorKind::kStereoEkfCaster)))
      entry = a;
  ASSERT_NE(entry, nullptr);
  entry->trigger();
  ASSERT_NE(controller->runner(), nullptr);
  EXPECT_EQ(controller->estimator(), EstimatorKind::kStereoEkfCaster);
  session.drive(0.3, 0.0);
  for (double t = 0.0; t < 10.0; t += 0.05)
    session.tick(0.05);
  const EstimatorRunner& runner = *controller->runner();
  EXPECT_GT(runner.metrics().distance_m, 2.0);
  EXPECT_GT(runner.metrics().readings, 50);
  EXPECT_GT(runner.metrics().acceptedFraction(), 0.5);
  EXPECT_LT(runner.metrics().max_position_error_m, 0.1);
  // Every 1 ms period predicted, although the GUI feeds one sample per frame.
  EXPECT_NEAR(static_cast<double>(runner.metrics().caster_periods),
              1000.0 * runner.metrics().duration_s, 60.0);
  const widgets::EstimatorOverlay& overlay = canvas_->estimatorOverlay();
  ASSERT_EQ(overlay.poses.size(), 3u);
  EXPECT_EQ(overlay.poses.back().label, QStringLiteral("EKF (J+)"));
  EXPECT_TRUE(overlay.poses.back().covariance.has_value());
  // A single update reports the J+ prediction and its adaptive noise with the sonar reading.
  lines.clear();
  controller->stepUpdate();
  const QString text = lines.join('\n');
  EXPECT_TRUE(text.contains(QStringLiteral("caster J+ prediction"))) << text.toStdString();
  EXPECT_TRUE(text.contains(QStringLiteral("λ = 0.005"))) << text.toStdString();
  delete controller;
}

}  // namespace
}  // namespace irgs::gui
