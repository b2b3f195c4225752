// The Calibrate menu in the application, offscreen: the UMBmark wizard drives its squares on the
// session's robot through the Robot interface (a BehaviourController), the simulator's truth
// pre-fills the measured ends, and the analysed corrections are written to the profile.

#include <gtest/gtest.h>

#include <QAction>
#include <QMenu>
#include <QPushButton>
#include <QSettings>
#include <QTableWidget>
#include <QTemporaryDir>
#include <QtTest/QTest>
#include <memory>

#include "app/gui/calibration_controller.hpp"
#include "app/gui/drive_script_player.hpp"
#include "app/gui/main_window.hpp"
#include "app/gui/session_controller.hpp"
#include "core/calibration/profile_calibration.hpp"
#include "tests/e2e/app_test_support.hpp"
#include "tests/e2e/main_window_fixture.hpp"
#include "widgets/calibration/gyro_wizard.hpp"
#include "widgets/calibration/umbmark_wizard.hpp"

namespace irgs::gui {
namespace {

class CalibrationGuiTest : public test::MainWindowFixture {
 protected:
  void SetUp() override {
    openWindow(test::squareRoom(6.0));
    profile_file_ = dir_.filePath(QStringLiteral("robot.json"));
    calibration_ = std::make_unique<CalibrationController>(*window_, *session_, profile_file_);
    session_->setSpeedFactor(8.0);
  }
  void TearDown() override {
    calibration_.reset();
    window_.reset();
  }

  QAction* menuAction(const QString& text) const {
    for (QAction* action : calibration_->menu()->actions())
      if (action->text().remove(QLatin1Char('&')) == text)
        return action;
    return nullptr;
  }

  // Ticks the session until the square is done (bounded).
  void driveUntilDone() {
    for (int i = 0; i < 4000 && calibration_->squareRunning(); ++i)
      session_->tick(0.05);
  }

  QString profile_file_;
  std::unique_ptr<CalibrationController> calibration_;
};

TEST_F(CalibrationGuiTest, TheUmbmarkWizardDrivesBothSquaresOnTheSessionRobotAndWritesTheProfile) {
  QAction* open = menuAction(QStringLiteral("Odometry (UMBmark)…"));
  ASSERT_NE(open, nullptr);
  open->trigger();
  widgets::UmbmarkWizard* wizard = calibration_->openUmbmarkWizard();
  ASSERT_NE(wizard, nullptr);
  EXPECT_TRUE(wizard->isVisible());
  EXPECT_EQ(wizard->outputFile(), profile_file_);
  wizard->setSource(widgets::UmbmarkWizard::Source::kRobot);
  wizard->setSide(1.5);

  for (const char* name : {"umbmarkDriveCw", "umbmarkDriveCcw"}) {
    auto* drive = wizard->findChild<QPushButton*>(QString::fromLatin1(name));
    ASSERT_NE(drive, nullptr);
    QTest::mouseClick(drive, Qt::LeftButton);
    EXPECT_TRUE(calibration_->squareRunning()) << wizard->robotStatusText().toStdString();
    driveUntilDone();
    ASSERT_FALSE(calibration_->squareRunning());
  }
  ASSERT_EQ(wizard->robotRunCount(), 2) << wizard->robotStatusText().toStdString();
  auto* table = wizard->findChild<QTableWidget*>(QStringLiteral("umbmarkRuns"));
  ASSERT_NE(table, nullptr);
  for (int row = 0; row < 2; ++row) {
    // The robot stopped where its odometry began; the simulator's truth is near it (its
    // odometry noise only) and pre-fills the measured end.
    EXPECT_LT(
        std::hypot(table->item(row, 1)->text().toDouble(), table->item(row, 2)->text().toDouble()),
        0.01);
    ASSERT_FALSE(table->item(row, 3)->text().isEmpty());
    EXPECT_LT(
        std::hypot(table->item(row, 3)->text().toDouble(), table->item(row, 4)->text().toDouble()),
        0.3);
  }
  wizard->analyseRobotRuns();
  ASSERT_TRUE(wizard->result() && wizard->result()->ok) << wizard->resultText().toStdString();
  ASSERT_TRUE(wizard->writeProfile());
  const RobotProfileResult written = loadRobotProfileFile(profile_file_.toStdString());
  ASSERT_TRUE(written.ok());
  EXPECT_TRUE(profileOdometry(*written.profile).error.empty());
  EXPECT_NEAR(written.profile->drive.wheelbase_m,
              session_->profile().drive.wheelbase_m * wizard->result()->analysis.wheelbase_ratio,
              1e-9);
}

TEST_F(CalibrationGuiTest, ASquareIsRefusedWhileADriveScriptDrivesTheRobot) {
  widgets::UmbmarkWizard* wizard = calibration_->openUmbmarkWizard();
  const DriveScript script({{0.0, {0.1, 0.0}}, {1e9, {0.0, 0.0}}});
  DriveScriptPlayer player(*session_, script);
  ASSERT_TRUE(player.start());
  calibration_->driveSquare(UmbmarkSquareConfig{});
  EXPECT_FALSE(calibration_->squareRunning());
  EXPECT_TRUE(wizard->robotStatusText().contains(QStringLiteral("another behaviour")));
  EXPECT_EQ(session_->runner().label(), QStringLiteral("Drive script"));  // still driving
}

TEST_F(CalibrationGuiTest, TheGyroWizardOpensFromTheMenuForTheSessionProfile) {
  QAction* open = menuAction(QStringLiteral("Gyro…"));
  ASSERT_NE(open, nullptr);
  open->trigger();
  widgets::GyroWizard* wizard = calibration_->openGyroWizard();
  ASSERT_NE(wizard, nullptr);
  EXPECT_TRUE(wizard->isVisible());
  EXPECT_EQ(calibration_->openGyroWizard(), wizard);  // one wizard, raised again
}

}  // namespace
}  // namespace irgs::gui
