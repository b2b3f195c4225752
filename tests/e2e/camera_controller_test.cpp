// The GUI's ceiling camera (CameraController): frames rendered from the simulated robot's true
// pose while the dock is visible, run through the vision pipelines and shown with their
// detections. Offscreen.

#include "app/gui/camera_controller.hpp"

#include <gtest/gtest.h>

#include <QDockWidget>
#include <QMainWindow>
#include <QMenu>
#include <QMenuBar>

#include "app/gui/session_controller.hpp"
#include "app_test_support.hpp"
#include "widgets/camera/camera_panel.hpp"

namespace irgs::gui {
namespace {

// The test room with a marker 0.8 m ahead of the start and a light beyond it.
WorldMap roomWithCeiling() {
  WorldMap map = test::squareRoom(2.5);
  map.ceiling_height_m = 2.5;
  CeilingMarker marker;
  marker.id = "M0";
  marker.position = Vec2(0.8, 0.3);
  map.markers.push_back(marker);
  CeilingLight light;
  light.id = "L0";
  light.tube = {Vec2(1.2, -0.6), Vec2(1.2, 0.6)};
  map.lights.push_back(light);
  return map;
}

class CameraControllerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    test::ensureApp();
    session_ = std::make_unique<SessionController>(test::thesisRobot(), test::simulatedFactory());
    session_->loadWorld(roomWithCeiling(), QStringLiteral("room.json"));
    window_ = std::make_unique<QMainWindow>();
    view_menu_ = window_->menuBar()->addMenu(QStringLiteral("&View"));
    view_menu_->setObjectName(QStringLiteral("viewMenu"));
    window_->resize(900, 700);
    controller_ = new CameraController(*session_, *window_);
    window_->show();
  }
  void run(double seconds) {
    for (double t = 0.0; t < seconds; t += 0.05)
      session_->tick(0.05);
  }

  std::unique_ptr<SessionController> session_;
  std::unique_ptr<QMainWindow> window_;
  QMenu* view_menu_ = nullptr;
  CameraController* controller_ = nullptr;
};

TEST_F(CameraControllerTest, RendersNothingWhileTheDockIsHidden) {
  EXPECT_TRUE(controller_->dock().isHidden());
  EXPECT_TRUE(view_menu_->actions().contains(controller_->dock().toggleViewAction()));
  run(1.0);
  EXPECT_EQ(controller_->framesShown(), 0);
}

TEST_F(CameraControllerTest, ShowsFramesAFewTimesASecondWithTheMarkerDetected) {
  controller_->setMinWallPeriodMs(0);  // the test ticks faster than real time
  controller_->dock().show();
  run(2.0);
  // 4 Hz of simulated time (plus the frame shown when the dock opened).
  EXPECT_GE(controller_->framesShown(), 7);
  EXPECT_LE(controller_->framesShown(), 10);
  const widgets::CameraPanel& panel = controller_->panel();
  EXPECT_TRUE(panel.frameView().hasImage());
  EXPECT_TRUE(panel.topView().hasImage());
  EXPECT_TRUE(panel.statusText().contains(QStringLiteral("1 marker")))
      << panel.statusText().toStdString();
  EXPECT_TRUE(panel.statusText().contains(QStringLiteral("1 light")))
      << panel.statusText().toStdString();
}

TEST_F(CameraControllerTest, FastSimulationDoesNotRenderMoreThanTheWallClockAllows) {
  controller_->setMinWallPeriodMs(60'000);
  controller_->dock().show();  // one frame on showing
  run(2.0);
  EXPECT_EQ(controller_->framesShown(), 1);
}

TEST_F(CameraControllerTest, AutomaticTiltFollowsTheTiltLawToTheNearestMarkerAhead) {
  const CeilingCameraConfig& cam = controller_->camera();
  const Pose2 start{0.0, 0.0, 0.0};
  const double d = (Vec2(0.8, 0.3) - Vec2(cam.mount.x_m, cam.mount.y_m)).norm();
  EXPECT_NEAR(controller_->autoTiltRad(start), cam.tilt.tiltFor(d), 1e-12);
  // Facing away from the marker: nothing ahead, the camera looks far (35 deg).
  EXPECT_NEAR(controller_->autoTiltRad(Pose2{0.0, 0.0, kPi}), cam.tilt.min_tilt_rad, 1e-12);
}

TEST_F(CameraControllerTest, AFixedTiltIsUsedAsSet) {
  controller_->panel().setFixedTiltDeg(40.0);
  controller_->dock().show();
  ASSERT_TRUE(controller_->showFrameAt(Pose2{0.0, 0.0, 0.0}, 0.0));
  EXPECT_TRUE(controller_->panel().statusText().contains(QStringLiteral("tilt 40.0")));
}

}  // namespace
}  // namespace irgs::gui
