// The main window's robot-link mode in-process (offscreen) against irgs-robot served over TCP:
// the mode switch opens the connection dialog (replaced by a stub here), connecting makes the
// session's robot a linked one, shows the health panel and link state, disables the simulation
// controls and feeds the console; going back to the simulator undoes all of it.

#include <gtest/gtest.h>

#include <QAction>
#include <QGroupBox>
#include <QLabel>
#include <QRadioButton>
#include <QSettings>
#include <QTemporaryDir>
#include <QTest>

#include "app/gui/link_controller.hpp"
#include "app/gui/link_ui.hpp"
#include "app/gui/main_window.hpp"
#include "app/gui/session_controller.hpp"
#include "app_test_support.hpp"
#include "child_process.hpp"
#include "tests/e2e/main_window_fixture.hpp"
#include "widgets/command/command_panel.hpp"
#include "widgets/console/console_widget.hpp"
#include "widgets/link/link_health_panel.hpp"

namespace irgs::gui {
namespace {

constexpr int kConnectTimeout_ms = 60000;  // a loaded 2-core machine

class LinkUiTest : public test::MainWindowFixture {
 protected:
  void SetUp() override {
    openWindow(test::squareRoom());
    window_->restoreSettings(QSize(1200, 800));
    window_->show();
    ASSERT_TRUE(QTest::qWaitForWindowExposed(window_.get()));
    session_->start();
  }
  void TearDown() override {
    window_.reset();
    session_.reset();  // the linked robot (and its io thread) goes with the session
    robot_.reset();
  }

  // irgs-robot as a TCP server on a free port; returns its URL.
  QString startRobot() {
    robot_ = std::make_unique<irgs::test::ChildProcess>(
        std::vector<std::string>{IRGS_ROBOT_EXE, "--tcp", "0", "--seed", "5"});
    const auto deadline = irgs::test::Clock::now() + std::chrono::seconds(30);
    while (auto line = robot_->readLine(deadline)) {
      if (line->rfind("tcp ", 0) == 0)
        return QStringLiteral("tcp://127.0.0.1:%1").arg(QString::fromStdString(line->substr(4)));
    }
    ADD_FAILURE() << "irgs-robot announced no TCP port";
    return {};
  }

  QRadioButton* radio(const char* name) const {
    return window_->commandPanel().findChild<QRadioButton*>(QLatin1String(name));
  }
  LinkUi& link() const { return window_->linkUi(); }

  std::unique_ptr<irgs::test::ChildProcess> robot_;
};

TEST_F(LinkUiTest, CancellingTheConnectionDialogStaysInTheSimulator) {
  int asked = 0;
  link().setDialogRunner([&asked](widgets::ConnectionDialogOptions) -> std::optional<QString> {
    ++asked;
    return std::nullopt;
  });
  radio("modeLinked")->click();
  EXPECT_EQ(asked, 1);
  EXPECT_EQ(window_->commandPanel().mode(), widgets::RobotMode::kSimulator);
  EXPECT_NE(session_->simulationControl(), nullptr);
  EXPECT_TRUE(link().healthPanel().isHidden());
}

TEST_F(LinkUiTest, ABadUrlIsReportedInTheConsoleAndChangesNothing) {
  const QString problem = link().connectTo(QStringLiteral("ftp://robot"));
  EXPECT_FALSE(problem.isEmpty());
  EXPECT_NE(session_->simulationControl(), nullptr);
  EXPECT_EQ(window_->commandPanel().mode(), widgets::RobotMode::kSimulator);
  // The console flushes on a short timer.
  EXPECT_TRUE(QTest::qWaitFor(
      [&] { return window_->console().visibleText().contains(QStringLiteral("Cannot connect")); },
      5000));
}

TEST_F(LinkUiTest, RobotLinkModeConnectsShowsHealthDrivesAndGoesBackToTheSimulator) {
  const QString url = startRobot();
  ASSERT_FALSE(url.isEmpty());
  widgets::ConnectionDialogOptions seen;
  link().setDialogRunner([&](widgets::ConnectionDialogOptions options) -> std::optional<QString> {
    seen = options;
    return url;
  });
  radio("modeLinked")->click();
  ASSERT_TRUE(link().controller().linked());
  EXPECT_TRUE(static_cast<bool>(seen.validate));
  EXPECT_EQ(session_->simulationControl(), nullptr);
  EXPECT_EQ(window_->commandPanel().mode(), widgets::RobotMode::kLinkedRobot);
  EXPECT_FALSE(link().healthPanel().isHidden());
  EXPECT_TRUE(window_->commandPanel().behavioursVisible());
  for (QAction* action : window_->findChildren<QAction*>()) {
    if (action->text().remove(QLatin1Char('&')) == QStringLiteral("Step")) {
      EXPECT_FALSE(action->isEnabled()) << "simulation stepping in linked mode";
    }
  }
  EXPECT_EQ(settings_->value(QString::fromLatin1(kLastLinkUrlKey)).toString(), url);

  ASSERT_TRUE(QTest::qWaitFor(
      [&] { return link().controller().health().state == widgets::LinkHealthState::kConnected; },
      kConnectTimeout_ms));
  ASSERT_TRUE(QTest::qWaitFor([&] { return link().controller().rates().samples > 20; },
                              kConnectTimeout_ms));
  EXPECT_EQ(link().healthPanel().fieldText(QStringLiteral("linkState")),
            QStringLiteral("CONNECTED"));
  EXPECT_EQ(link().statusLabel().text(), QStringLiteral("link connected"));
  EXPECT_TRUE(window_->console().visibleText().contains(QStringLiteral("Link: ")));

  // Teleop through the session reaches the robot: its odometry turns.
  const double theta0 = session_->latestSample()->odometry_pose.theta;
  session_->drive(0.0, 0.8);
  EXPECT_TRUE(QTest::qWaitFor(
      [&] {
        return std::abs(wrapAngle(session_->latestSample()->odometry_pose.theta - theta0)) > 0.3;
      },
      kConnectTimeout_ms));
  session_->stopRobot();
  EXPECT_GT(session_->grid().exploredArea_m2(), 0.0);

  radio("modeSimulator")->click();
  EXPECT_FALSE(link().controller().linked());
  EXPECT_NE(session_->simulationControl(), nullptr);
  EXPECT_TRUE(link().healthPanel().isHidden());
  EXPECT_TRUE(link().statusLabel().isHidden());
  EXPECT_FALSE(window_->commandPanel().behavioursVisible());
}

}  // namespace
}  // namespace irgs::gui
