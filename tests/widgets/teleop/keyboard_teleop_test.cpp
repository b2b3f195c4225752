#include "widgets/teleop/keyboard_teleop.hpp"

#include <gtest/gtest.h>

#include <QApplication>
#include <QKeyEvent>
#include <QLineEdit>
#include <QSignalSpy>
#include <QVBoxLayout>
#include <QWidget>
#include <QtTest/QTest>

namespace irgs::widgets {
namespace {

constexpr double kV = 0.25;
constexpr double kW = 0.9;

class KeyboardTeleopTest : public ::testing::Test {
 protected:
  void SetUp() override {
    teleop.setSpeeds(kV, kW);
    qApp->installEventFilter(&teleop);
    target = new QWidget(&window);
    target->setFocusPolicy(Qt::StrongFocus);
    line_edit = new QLineEdit(&window);
    auto* layout = new QVBoxLayout(&window);
    layout->addWidget(target);
    layout->addWidget(line_edit);
  }
  void TearDown() override { qApp->removeEventFilter(&teleop); }

  void send(QEvent::Type type, int key, bool auto_repeat = false,
            Qt::KeyboardModifiers modifiers = Qt::NoModifier) {
    QKeyEvent event(type, key, modifiers, QString(), auto_repeat);
    QApplication::sendEvent(target, &event);
  }
  void press(int key) { send(QEvent::KeyPress, key); }
  void release(int key) { send(QEvent::KeyRelease, key); }
  std::pair<double, double> last(const QSignalSpy& spy) const {
    const QList<QVariant>& args = spy.last();
    return {args.at(0).toDouble(), args.at(1).toDouble()};
  }

  KeyboardTeleop teleop;
  QWidget window;
  QWidget* target = nullptr;
  QLineEdit* line_edit = nullptr;
};

TEST_F(KeyboardTeleopTest, UpDrivesForward) {
  QSignalSpy spy(&teleop, &KeyboardTeleop::commandChanged);
  press(Qt::Key_Up);
  ASSERT_EQ(spy.count(), 1);
  EXPECT_EQ(last(spy), std::make_pair(kV, 0.0));
}

TEST_F(KeyboardTeleopTest, UpAndLeftDriveAnArcAndReleasesStopEachAxis) {
  QSignalSpy spy(&teleop, &KeyboardTeleop::commandChanged);
  press(Qt::Key_Up);
  press(Qt::Key_Left);
  EXPECT_EQ(last(spy), std::make_pair(kV, kW));
  release(Qt::Key_Up);
  EXPECT_EQ(last(spy), std::make_pair(0.0, kW));
  release(Qt::Key_Left);
  EXPECT_EQ(last(spy), std::make_pair(0.0, 0.0));
  EXPECT_EQ(spy.count(), 4);
}

TEST_F(KeyboardTeleopTest, WasdWorksLikeTheArrows) {
  QSignalSpy spy(&teleop, &KeyboardTeleop::commandChanged);
  press(Qt::Key_S);
  press(Qt::Key_D);
  EXPECT_EQ(last(spy), std::make_pair(-kV, -kW));
  press(Qt::Key_Down);  // same axis twice: still one unit
  EXPECT_EQ(spy.count(), 2);
  release(Qt::Key_S);
  EXPECT_EQ(last(spy), std::make_pair(-kV, -kW));  // Down still held
  release(Qt::Key_Down);
  release(Qt::Key_D);
  EXPECT_EQ(last(spy), std::make_pair(0.0, 0.0));
}

TEST_F(KeyboardTeleopTest, SpaceStopsAndForgetsHeldKeys) {
  QSignalSpy stop(&teleop, &KeyboardTeleop::stopPressed);
  QSignalSpy spy(&teleop, &KeyboardTeleop::commandChanged);
  press(Qt::Key_Up);
  press(Qt::Key_Space);
  EXPECT_EQ(stop.count(), 1);
  EXPECT_EQ(last(spy), std::make_pair(0.0, 0.0));
  release(Qt::Key_Up);  // nothing left to release
  EXPECT_EQ(spy.count(), 2);
}

TEST_F(KeyboardTeleopTest, AutoRepeatIsIgnored) {
  QSignalSpy spy(&teleop, &KeyboardTeleop::commandChanged);
  press(Qt::Key_Up);
  // X11-style auto-repeat: release + press pairs flagged as auto-repeat while the key is held.
  for (int i = 0; i < 5; ++i) {
    send(QEvent::KeyRelease, Qt::Key_Up, true);
    send(QEvent::KeyPress, Qt::Key_Up, true);
  }
  EXPECT_EQ(spy.count(), 1);
  EXPECT_EQ(teleop.linearCommand(), kV);
  QSignalSpy stop(&teleop, &KeyboardTeleop::stopPressed);
  send(QEvent::KeyPress, Qt::Key_Space, true);
  EXPECT_EQ(stop.count(), 0);
}

TEST_F(KeyboardTeleopTest, KeysAreIgnoredWhileALineEditHasFocus) {
  window.show();
  window.activateWindow();
  ASSERT_TRUE(QTest::qWaitForWindowActive(&window));
  line_edit->setFocus();
  ASSERT_EQ(QApplication::focusWidget(), line_edit);
  QSignalSpy spy(&teleop, &KeyboardTeleop::commandChanged);
  QSignalSpy stop(&teleop, &KeyboardTeleop::stopPressed);
  QTest::keyClick(line_edit, Qt::Key_W);
  QTest::keyClick(line_edit, Qt::Key_Space);
  QTest::keyClick(line_edit, Qt::Key_Up);
  EXPECT_EQ(spy.count(), 0);
  EXPECT_EQ(stop.count(), 0);
  EXPECT_EQ(line_edit->text(), "w ");  // the text went to the line edit

  target->setFocus();
  QTest::keyPress(target, Qt::Key_W);
  EXPECT_EQ(spy.count(), 1);
  // Focus moves into the line edit while W is held: its release still stops.
  line_edit->setFocus();
  QTest::keyRelease(line_edit, Qt::Key_W);
  EXPECT_EQ(last(spy), std::make_pair(0.0, 0.0));
}

TEST_F(KeyboardTeleopTest, ShortcutsWithModifiersAreLeftAlone) {
  QSignalSpy spy(&teleop, &KeyboardTeleop::commandChanged);
  send(QEvent::KeyPress, Qt::Key_S, false, Qt::ControlModifier);
  EXPECT_EQ(spy.count(), 0);
}

TEST_F(KeyboardTeleopTest, DisablingStopsAndIgnoresKeys) {
  QSignalSpy spy(&teleop, &KeyboardTeleop::commandChanged);
  press(Qt::Key_Up);
  teleop.setEnabled(false);
  EXPECT_EQ(last(spy), std::make_pair(0.0, 0.0));
  press(Qt::Key_Up);
  EXPECT_EQ(spy.count(), 2);
}

TEST_F(KeyboardTeleopTest, LosingApplicationFocusReleasesKeys) {
  QSignalSpy spy(&teleop, &KeyboardTeleop::commandChanged);
  press(Qt::Key_Left);
  QEvent deactivate(QEvent::ApplicationDeactivate);
  QApplication::sendEvent(qApp, &deactivate);
  EXPECT_EQ(last(spy), std::make_pair(0.0, 0.0));
}

TEST_F(KeyboardTeleopTest, NewSpeedsApplyToHeldKeys) {
  QSignalSpy spy(&teleop, &KeyboardTeleop::commandChanged);
  press(Qt::Key_Up);
  teleop.setSpeeds(0.5, NAN);
  EXPECT_EQ(last(spy), std::make_pair(0.5, 0.0));
  press(Qt::Key_Right);
  EXPECT_EQ(last(spy), std::make_pair(0.5, -kW));
}

}  // namespace
}  // namespace irgs::widgets
