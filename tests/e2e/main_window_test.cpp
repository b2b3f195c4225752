// The main window offscreen: keyboard teleop drives the simulated robot, menus act on the
// session, a rejected map leaves the current one, settings round-trip.

#include "app/gui/main_window.hpp"

#include <gtest/gtest.h>

#include <QAction>
#include <QApplication>
#include <QMenuBar>
#include <QMessageBox>
#include <QSettings>
#include <QSplitter>
#include <QTemporaryDir>
#include <QTest>
#include <QTimer>
#include <algorithm>

#include "app/gui/map_file_actions.hpp"
#include "app/gui/session_controller.hpp"
#include "tests/e2e/app_test_support.hpp"
#include "tests/e2e/main_window_fixture.hpp"
#include "widgets/canvas/map_canvas.hpp"
#include "widgets/command/command_panel.hpp"
#include "widgets/console/console_widget.hpp"
#include "widgets/teleop/keyboard_teleop.hpp"

namespace irgs::gui {
namespace {

class MainWindowTest : public test::MainWindowFixture {
 protected:
  void SetUp() override {
    openWindow(test::squareRoom());
    window_->restoreSettings(QSize(1200, 800));
    window_->show();
    ASSERT_TRUE(QTest::qWaitForWindowExposed(window_.get()));
    window_->activateWindow();
    window_->canvas().setFocus();
  }

  void run(double seconds) {
    for (int i = 0; i < static_cast<int>(seconds / 0.02 + 0.5); ++i)
      session_->tick(0.02);
  }

  Pose2 pose() const { return session_->latestSample()->odometry_pose; }

  QAction* findAction(const QString& text) const {
    for (QAction* action : window_->findChildren<QAction*>()) {
      if (action->text().remove(QLatin1Char('&')) == text)
        return action;
    }
    return nullptr;
  }
};

TEST_F(MainWindowTest, UpArrowHeldDrivesTheRobotForwardAndReleaseStopsIt) {
  QTest::keyPress(&window_->canvas(), Qt::Key_Up);
  run(1.5);
  EXPECT_GT(session_->command().linear_mps, 0.0);
  EXPECT_GT(pose().x, 0.1);
  QTest::keyRelease(&window_->canvas(), Qt::Key_Up);
  EXPECT_DOUBLE_EQ(session_->command().linear_mps, 0.0);
  run(1.0);
  const double stopped_x = pose().x;
  run(1.0);
  EXPECT_NEAR(pose().x, stopped_x, 1e-3);
}

TEST_F(MainWindowTest, WasdTurnsTheRobotAndSpaceStopsIt) {
  QTest::keyPress(&window_->canvas(), Qt::Key_A);
  run(1.0);
  EXPECT_GT(pose().theta, 0.2);  // A = turn left = counter-clockwise
  QTest::keyClick(&window_->canvas(), Qt::Key_Space);
  EXPECT_DOUBLE_EQ(session_->command().angular_radps, 0.0);
  QTest::keyRelease(&window_->canvas(), Qt::Key_A);
}

TEST_F(MainWindowTest, TeleopUsesTheCommandPanelSpeeds) {
  window_->commandPanel().setDriveSpeeds(0.1, 0.5);
  window_->teleop().setSpeeds(0.1, 0.5);
  QTest::keyPress(&window_->canvas(), Qt::Key_W);
  EXPECT_NEAR(session_->command().linear_mps, 0.1, 1e-9);
  QTest::keyRelease(&window_->canvas(), Qt::Key_W);
}

TEST_F(MainWindowTest, PauseActionStopsSimulatedTime) {
  QAction* pause = findAction(QStringLiteral("Pause"));
  ASSERT_NE(pause, nullptr);
  pause->trigger();
  EXPECT_TRUE(session_->paused());
  EXPECT_TRUE(window_->commandPanel().paused());
  const double t = session_->displayTime_s();
  run(0.5);
  EXPECT_DOUBLE_EQ(session_->displayTime_s(), t);
  QAction* run_action = findAction(QStringLiteral("Run"));
  ASSERT_NE(run_action, nullptr);
  run_action->trigger();
  EXPECT_FALSE(session_->paused());
}

TEST_F(MainWindowTest, ResetRobotActionReturnsToStartAndRestartsTheTrail) {
  session_->drive(0.25, 0.0);
  run(2.0);
  EXPECT_GT(window_->canvas().trailSize(), 5u);
  QAction* reset = findAction(QStringLiteral("Reset Robot to Start Pose"));
  ASSERT_NE(reset, nullptr);
  reset->trigger();
  EXPECT_LE(window_->canvas().trailSize(), 1u);
  EXPECT_DOUBLE_EQ(pose().x, 0.0);
  EXPECT_DOUBLE_EQ(session_->command().linear_mps, 0.0);
}

TEST_F(MainWindowTest, RejectedMapShowsTheDiagnosticsAndKeepsTheCurrentMap) {
  QString dialog_text;
  QTimer::singleShot(0, [&dialog_text] {
    if (auto* box = qobject_cast<QMessageBox*>(QApplication::activeModalWidget())) {
      dialog_text = box->informativeText();
      box->close();
    }
  });
  const QString broken = QStringLiteral(IRGS_SOURCE_DIR "/tests/e2e/data/malformed_map.json");
  EXPECT_FALSE(window_->mapFiles().openMap(broken));
  EXPECT_EQ(session_->worldMap().name, "test room");
  EXPECT_TRUE(dialog_text.contains(QStringLiteral("malformed_map.json:")))
      << dialog_text.toStdString();
  EXPECT_TRUE(window_->console().visibleText().contains(QStringLiteral("rejected")));
  EXPECT_TRUE(window_->console().visibleText().contains(QStringLiteral("malformed_map.json:7:")));
}

TEST_F(MainWindowTest, OpeningTheBundledMapUpdatesTitleAndRecentFiles) {
  const QString path = QStringLiteral(IRGS_SOURCE_DIR "/resources/maps/default.json");
  ASSERT_TRUE(window_->mapFiles().openMap(path));
  EXPECT_TRUE(window_->windowTitle().contains(QStringLiteral("default.json")))
      << window_->windowTitle().toStdString();
  EXPECT_EQ(window_->mapFiles().recentFiles().value(0), QFileInfo(path).absoluteFilePath());
  EXPECT_EQ(window_->mapFiles().recentMenu()->actions().isEmpty(), false);
}

TEST_F(MainWindowTest, LayerVisibilityAndSpeedsPersistAcrossWindows) {
  QAction* trail = findAction(QStringLiteral("Trail"));
  ASSERT_NE(trail, nullptr);
  trail->setChecked(false);
  EXPECT_FALSE(window_->canvas().layerVisible(widgets::MapCanvas::Layer::kTrail));
  window_->commandPanel().setDriveSpeeds(0.15, 0.6);
  window_->saveSettings();
  window_.reset();

  MainWindow second(*session_, *settings_);
  second.restoreSettings(QSize(1000, 700));
  EXPECT_FALSE(second.canvas().layerVisible(widgets::MapCanvas::Layer::kTrail));
  EXPECT_NEAR(second.commandPanel().linearSpeed(), 0.15, 1e-6);
}

TEST_F(MainWindowTest, LayoutPutsTheCanvasLeftAndTheSideColumnRight) {
  const auto* splitter = qobject_cast<QSplitter*>(window_->centralWidget());
  ASSERT_NE(splitter, nullptr);
  EXPECT_EQ(splitter->widget(0), &window_->canvas());
  const QList<int> sizes = splitter->sizes();
  ASSERT_EQ(sizes.size(), 2);
  EXPECT_GT(sizes[0], sizes[1]);
  // The side column gets kSideColumnWidth, or its widgets' minimum width when that is larger.
  const int side_minimum = splitter->widget(1)->minimumSizeHint().width();
  EXPECT_GE(sizes[1], std::min(MainWindow::kSideColumnWidth, side_minimum));
  EXPECT_LE(sizes[1], std::max(MainWindow::kSideColumnWidth, side_minimum) + 10);
  EXPECT_GT(window_->commandPanel().geometry().height(), 0);
  EXPECT_LT(window_->commandPanel().mapTo(window_.get(), QPoint(0, 0)).y(),
            window_->console().mapTo(window_.get(), QPoint(0, 0)).y());
}

}  // namespace
}  // namespace irgs::gui
