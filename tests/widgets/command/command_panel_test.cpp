#include "widgets/command/command_panel.hpp"

#include <gtest/gtest.h>

#include <QComboBox>
#include <QDoubleSpinBox>
#include <QRadioButton>
#include <QSignalSpy>
#include <QToolButton>
#include <QtTest/QTest>

#include "core/geometry/types.hpp"

namespace irgs::widgets {
namespace {

template <typename T>
T* child(const QWidget& parent, const char* name) {
  T* w = parent.findChild<T*>(QLatin1String(name));
  EXPECT_NE(w, nullptr) << name;
  return w;
}

TEST(CommandPanel, StopButtonEmitsStopRequested) {
  CommandPanel panel;
  QSignalSpy stop(&panel, &CommandPanel::stopRequested);
  QTest::mouseClick(child<QToolButton>(panel, "driveStop"), Qt::LeftButton);
  EXPECT_EQ(stop.count(), 1);
}

TEST(CommandPanel, SpeedComboEmitsZeroForMax) {
  CommandPanel panel;
  QSignalSpy speed(&panel, &CommandPanel::simSpeedChanged);
  auto* combo = child<QComboBox>(panel, "simSpeed");
  combo->setCurrentIndex(combo->findText("max"));
  ASSERT_EQ(speed.count(), 1);
  EXPECT_EQ(speed.at(0).at(0).toDouble(), 0.0);
  combo->setCurrentIndex(combo->findText(QStringLiteral("×10")));
  EXPECT_EQ(speed.at(1).at(0).toDouble(), 10.0);
}

TEST(CommandPanel, SettersDoNotEmit) {
  CommandPanel panel;
  QSignalSpy speed(&panel, &CommandPanel::simSpeedChanged);
  QSignalSpy paused(&panel, &CommandPanel::pausedChanged);
  QSignalSpy mode(&panel, &CommandPanel::modeRequested);
  QSignalSpy speeds(&panel, &CommandPanel::driveSpeedsChanged);
  panel.setSimSpeed(0.0);
  EXPECT_EQ(panel.simSpeed(), 0.0);
  panel.setSimSpeed(5.0);  // unusual factor: gets its own entry
  EXPECT_EQ(panel.simSpeed(), 5.0);
  panel.setPaused(true);
  EXPECT_TRUE(panel.paused());
  panel.setMode(RobotMode::kLinkedRobot);
  EXPECT_EQ(panel.mode(), RobotMode::kLinkedRobot);
  panel.setDriveSpeeds(0.35, degToRad(90.0));
  EXPECT_NEAR(panel.linearSpeed(), 0.35, 1e-9);
  EXPECT_NEAR(panel.angularSpeed(), degToRad(90.0), 1e-9);
  panel.setDriveSpeeds(NAN, -1.0);  // ignored
  EXPECT_NEAR(panel.linearSpeed(), 0.35, 1e-9);
  EXPECT_EQ(speed.count() + paused.count() + mode.count() + speeds.count(), 0);
}

TEST(CommandPanel, HoldingADriveButtonDrivesAndReleasingStops) {
  CommandPanel panel;
  panel.setDriveSpeeds(0.3, degToRad(60.0));  // spin boxes hold 0.01 m/s and 1 deg/s steps
  QSignalSpy drive(&panel, &CommandPanel::driveRequested);
  auto* arc = child<QToolButton>(panel, "driveForwardLeft");
  QTest::mousePress(arc, Qt::LeftButton);
  ASSERT_EQ(drive.count(), 1);
  EXPECT_NEAR(drive.at(0).at(0).toDouble(), 0.3, 1e-9);
  EXPECT_NEAR(drive.at(0).at(1).toDouble(), degToRad(60.0), 1e-9);
  QTest::mouseRelease(arc, Qt::LeftButton);
  ASSERT_EQ(drive.count(), 2);
  EXPECT_EQ(drive.at(1).at(0).toDouble(), 0.0);
  EXPECT_EQ(drive.at(1).at(1).toDouble(), 0.0);

  QTest::mousePress(child<QToolButton>(panel, "driveBack"), Qt::LeftButton);
  EXPECT_NEAR(drive.at(2).at(0).toDouble(), -0.3, 1e-9);
  EXPECT_EQ(drive.at(2).at(1).toDouble(), 0.0);
  QTest::mouseRelease(child<QToolButton>(panel, "driveBack"), Qt::LeftButton);
}

TEST(CommandPanel, UserActionsEmit) {
  CommandPanel panel;
  QSignalSpy paused(&panel, &CommandPanel::pausedChanged);
  QSignalSpy step(&panel, &CommandPanel::stepRequested);
  QSignalSpy mode(&panel, &CommandPanel::modeRequested);
  QSignalSpy speeds(&panel, &CommandPanel::driveSpeedsChanged);
  auto* step_button = child<QToolButton>(panel, "simStep");
  EXPECT_FALSE(step_button->isEnabled());  // stepping only while paused
  QTest::mouseClick(child<QToolButton>(panel, "simPause"), Qt::LeftButton);
  ASSERT_EQ(paused.count(), 1);
  EXPECT_TRUE(paused.at(0).at(0).toBool());
  EXPECT_TRUE(step_button->isEnabled());
  QTest::mouseClick(step_button, Qt::LeftButton);
  EXPECT_EQ(step.count(), 1);
  child<QRadioButton>(panel, "modeLinked")->click();
  ASSERT_EQ(mode.count(), 1);
  EXPECT_EQ(mode.at(0).at(0).value<RobotMode>(), RobotMode::kLinkedRobot);
  child<QDoubleSpinBox>(panel, "driveAngularSpeed")->setValue(90.0);
  ASSERT_EQ(speeds.count(), 1);
  EXPECT_NEAR(speeds.at(0).at(1).toDouble(), degToRad(90.0), 1e-9);
}

TEST(CommandPanel, LinkedModeCanBeUnavailableWithAReason) {
  CommandPanel panel;
  panel.setLinkedModeAvailable(false, "No serial port found");
  auto* linked = child<QRadioButton>(panel, "modeLinked");
  EXPECT_FALSE(linked->isEnabled());
  EXPECT_EQ(linked->toolTip(), "No serial port found");
  panel.setLinkedModeAvailable(true, {});
  EXPECT_TRUE(linked->isEnabled());
}

TEST(CommandPanel, BehaviourButtonsAskForTheDistanceAndAngleSetAndAreHiddenInTheSimulator) {
  CommandPanel panel;
  EXPECT_FALSE(panel.behavioursVisible());
  panel.setBehavioursVisible(true);
  EXPECT_TRUE(panel.behavioursVisible());
  QSignalSpy move(&panel, &CommandPanel::moveDistanceRequested);
  QSignalSpy turn(&panel, &CommandPanel::turnAngleRequested);
  child<QDoubleSpinBox>(panel, "behaviourDistance")->setValue(-0.5);
  child<QDoubleSpinBox>(panel, "behaviourAngle")->setValue(-45.0);
  child<QToolButton>(panel, "behaviourMove")->click();
  child<QToolButton>(panel, "behaviourTurn")->click();
  ASSERT_EQ(move.count(), 1);
  ASSERT_EQ(turn.count(), 1);
  EXPECT_DOUBLE_EQ(move.at(0).at(0).toDouble(), -0.5);
  EXPECT_NEAR(turn.at(0).at(0).toDouble(), degToRad(-45.0), 1e-12);
  panel.setBehavioursVisible(false);
  EXPECT_FALSE(panel.behavioursVisible());
}

}  // namespace
}  // namespace irgs::widgets
