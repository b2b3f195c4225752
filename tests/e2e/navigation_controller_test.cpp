// The GUI's landmark navigation (NavigationController): the "Navigate" tab plans a route on the
// map's topological graph and a delivery runs in the simulator, with the route, state,
// avoidance vectors and moving obstacles on the canvas overlay. Offscreen.
// With IRGS_NAV_SCREENSHOT=FILE.png the window is photographed mid-run (docs/images/).

#include "app/gui/navigation_controller.hpp"

#include <gtest/gtest.h>

#include <QHBoxLayout>
#include <QLabel>
#include <QPushButton>
#include <QTabWidget>
#include <cstdlib>

#include "app/gui/behaviour_controller.hpp"
#include "app/gui/session_controller.hpp"
#include "app_test_support.hpp"
#include "core/navigation/delivery_behaviour.hpp"
#include "core/world/map_file.hpp"
#include "widgets/canvas/map_canvas.hpp"
#include "widgets/navigation/navigation_panel.hpp"

namespace irgs::gui {
namespace {

WorldMap bundledMap(const char* name) {
  auto r = loadMapFile(std::string(IRGS_SOURCE_DIR) + "/resources/maps/" + name);
  if (!r.map)
    throw std::runtime_error("bundled map does not load");
  return *r.map;
}

RobotProfile deliveryRobot() {
  auto r =
      loadRobotProfileFile(std::string(IRGS_SOURCE_DIR) + "/resources/robots/delivery_002.json");
  if (!r.profile)
    throw std::runtime_error("delivery_002.json does not load");
  return *r.profile;
}

class NavigationControllerTest : public ::testing::Test {
 protected:
  void load(const char* map) {
    test::ensureApp();
    session_ = std::make_unique<SessionController>(deliveryRobot(), test::simulatedFactory(3));
    window_ = std::make_unique<QWidget>();
    auto* layout = new QHBoxLayout(window_.get());
    canvas_ = new widgets::MapCanvas(window_.get());
    tabs_ = new QTabWidget(window_.get());
    layout->addWidget(canvas_, 1);
    layout->addWidget(tabs_);
    window_->resize(1200, 760);
    session_->loadWorld(bundledMap(map), QString::fromLatin1(map));
    canvas_->setWorldMap(session_->worldMap());
    canvas_->setRobotProfile(session_->profile());
    QObject::connect(session_.get(), &SessionController::robotStateChanged, canvas_,
                     &widgets::MapCanvas::setRobotState);
    controller_ = std::make_unique<NavigationController>(*session_, *canvas_, *tabs_);
    window_->show();
    canvas_->zoomToFit();
  }
  // Ticks the session (simulated seconds) until the delivery finishes or `seconds` pass;
  // photographs the window at `photo_s` when IRGS_NAV_SCREENSHOT is set.
  void run(double seconds, double photo_s = -1.0) {
    for (double t = 0.0; t < seconds && controller_->running(); t += 0.05) {
      session_->tick(0.05);
      if (photo_s >= 0.0 && t < photo_s && t + 0.05 >= photo_s) {
        if (const char* out = std::getenv("IRGS_NAV_SCREENSHOT")) {
          QApplication::processEvents();
          window_->grab().save(QString::fromLocal8Bit(out));
        }
      }
    }
  }

  std::unique_ptr<SessionController> session_;
  std::unique_ptr<QWidget> window_;
  widgets::MapCanvas* canvas_ = nullptr;
  QTabWidget* tabs_ = nullptr;
  std::unique_ptr<NavigationController> controller_;
};

TEST_F(NavigationControllerTest, TheNavigateTabListsTheGraphNodes) {
  load("delivery_floor_002.json");
  ASSERT_EQ(tabs_->count(), 1);
  EXPECT_EQ(tabs_->tabText(0), QStringLiteral("Navigate"));
  EXPECT_EQ(controller_->panel().startNode(), QStringLiteral("0"));
  EXPECT_EQ(controller_->panel().goalNode(), QStringLiteral("6"));
  EXPECT_TRUE(controller_->panel().goButton().isEnabled());
  EXPECT_FALSE(controller_->panel().abortButton().isEnabled());
}

TEST_F(NavigationControllerTest, GoDeliversFromNodeZeroToSixWithTheRouteOnTheCanvas) {
  load("delivery_floor_002_people.json");
  controller_->panel().goButton().click();
  ASSERT_TRUE(controller_->running());
  EXPECT_TRUE(controller_->panel().abortButton().isEnabled());
  run(10.0);
  const widgets::NavigationOverlay& mid = canvas_->navigationOverlay();
  EXPECT_EQ(mid.route.size(), 5u);
  EXPECT_EQ(mid.moving_obstacles.size(), 3u);
  EXPECT_TRUE(mid.robot.has_value());
  EXPECT_GT(mid.move.norm(), 0.0);
  EXPECT_FALSE(mid.state.isEmpty());
  run(140.0, 40.0);
  EXPECT_FALSE(controller_->running());
  ASSERT_NE(controller_->delivery(), nullptr);
  EXPECT_TRUE(controller_->delivery()->navigator().arrived());
  const Pose2 end = session_->latestSample()->true_pose.value();
  EXPECT_LT((end.position() - Vec2(2.0, 10.0)).norm(), 0.5);
  EXPECT_TRUE(controller_->panel().goButton().isEnabled());
}

TEST_F(NavigationControllerTest, AbortStopsTheRobot) {
  load("delivery_floor_002.json");
  ASSERT_TRUE(controller_->go(QStringLiteral("0"), QStringLiteral("6")));
  run(3.0);
  controller_->panel().abortButton().click();
  EXPECT_FALSE(controller_->running());
  EXPECT_TRUE(controller_->panel().stateLabel().text().contains(QStringLiteral("aborted")));
}

TEST_F(NavigationControllerTest, AnUnknownNodeIsRefused) {
  load("delivery_floor_002.json");
  EXPECT_FALSE(controller_->go(QStringLiteral("0"), QStringLiteral("N9")));
  EXPECT_FALSE(controller_->running());
}

}  // namespace
}  // namespace irgs::gui
