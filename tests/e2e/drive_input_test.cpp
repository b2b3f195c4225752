// Hand-held driving in the application, offscreen: the gamepad teleop on a fake device source
// (CI has no gamepad), and the drive pad in the Drive tab, both driving the session's robot
// through the same path as the keyboard.

#include <gtest/gtest.h>

#include <QLabel>
#include <QSettings>
#include <QSignalSpy>
#include <QTemporaryDir>
#include <QtTest/QTest>
#include <memory>

#include "app/gui/drive_input_controller.hpp"
#include "app/gui/gamepad_teleop.hpp"
#include "app/gui/main_window.hpp"
#include "app/gui/session_controller.hpp"
#include "tests/e2e/app_test_support.hpp"
#include "tests/e2e/main_window_fixture.hpp"
#include "widgets/command/command_panel.hpp"
#include "widgets/teleop/drive_pad.hpp"

namespace irgs::gui {
namespace {

// A gamepad the test plugs in, moves and unplugs.
struct FakeDevice {
  std::optional<GamepadState> state;
  std::string name = "Fake Pad";
};

class FakeSource : public GamepadSource {
 public:
  explicit FakeSource(std::shared_ptr<FakeDevice> device) : device_(std::move(device)) {}
  std::optional<GamepadState> poll() override { return device_->state; }
  std::string deviceName() const override { return device_->state ? device_->name : ""; }
  std::string unavailableReason() const override { return {}; }

 private:
  std::shared_ptr<FakeDevice> device_;
};

constexpr int kDeadman = 9;  // SDL_CONTROLLER_BUTTON_LEFTSHOULDER, the default

GamepadState stick(double left_y, double right_x, bool deadman) {
  GamepadState s;
  s.axes[1] = left_y;
  s.axes[2] = right_x;
  if (deadman)
    s.buttons = 1u << kDeadman;
  return s;
}

MotionLimits limits() {
  MotionLimits l;
  l.max_speed_mps = 0.6;
  l.max_turn_rate_radps = 1.6;
  return l;
}

TEST(GamepadTeleop, DrivesOnlyWhileTheDeadManIsHeldAndStopsOnReleaseOrUnplug) {
  test::ensureApp();
  auto device = std::make_shared<FakeDevice>();
  GamepadTeleop teleop(std::make_unique<FakeSource>(device), limits());
  QSignalSpy commands(&teleop, &GamepadTeleop::commandChanged);
  QSignalSpy released(&teleop, &GamepadTeleop::released);
  QSignalSpy connection(&teleop, &GamepadTeleop::connectionChanged);

  teleop.pollOnce();  // no gamepad: nothing, quietly
  EXPECT_EQ(connection.count(), 0);
  EXPECT_TRUE(teleop.statusText().contains(QStringLiteral("none connected")));

  device->state = stick(-1.0, 0.0, false);  // plugged in, stick pushed, dead-man not held
  teleop.pollOnce();
  ASSERT_EQ(connection.count(), 1);
  EXPECT_TRUE(connection.last().at(0).toBool());
  EXPECT_TRUE(teleop.statusText().contains(QStringLiteral("Fake Pad")));
  EXPECT_EQ(commands.count(), 0);

  device->state = stick(-1.0, 0.0, true);
  teleop.pollOnce();
  ASSERT_EQ(commands.count(), 1);
  EXPECT_DOUBLE_EQ(commands.last().at(0).toDouble(), 0.3);  // half the profile's 0.6 m/s
  teleop.pollOnce();
  EXPECT_EQ(commands.count(), 1);          // unchanged: not re-sent
  device->state = stick(0.05, 1.0, true);  // inside the deadband forward, full right
  teleop.pollOnce();
  ASSERT_EQ(commands.count(), 2);
  EXPECT_DOUBLE_EQ(commands.last().at(0).toDouble(), 0.0);
  EXPECT_DOUBLE_EQ(commands.last().at(1).toDouble(), -0.8);

  device->state = stick(-1.0, 0.0, false);  // dead-man let go with the stick still pushed
  teleop.pollOnce();
  EXPECT_EQ(released.count(), 1);
  EXPECT_FALSE(teleop.driving());
  teleop.pollOnce();
  EXPECT_EQ(released.count(), 1);  // once

  device->state = stick(-1.0, 0.0, true);
  teleop.pollOnce();
  EXPECT_TRUE(teleop.driving());
  device->state.reset();  // unplugged while driving
  teleop.pollOnce();
  EXPECT_EQ(released.count(), 2);
  EXPECT_FALSE(connection.last().at(0).toBool());
}

class DriveInputTest : public test::MainWindowFixture {
 protected:
  void SetUp() override {
    openWindow(test::squareRoom());
    device_ = std::make_shared<FakeDevice>();
    input_ = std::make_unique<DriveInputController>(window_->commandPanel(), *session_,
                                                    std::make_unique<FakeSource>(device_));
    input_->gamepad().stop();  // the test polls
    window_->resize(1200, 900);
    window_->show();
    ASSERT_TRUE(QTest::qWaitForWindowExposed(window_.get()));
  }
  void TearDown() override {
    input_.reset();
    window_.reset();
  }
  void run(double seconds) {
    for (int i = 0; i < static_cast<int>(seconds / 0.02 + 0.5); ++i)
      session_->tick(0.02);
  }
  Pose2 pose() const { return session_->latestSample()->odometry_pose; }

  std::shared_ptr<FakeDevice> device_;
  std::unique_ptr<DriveInputController> input_;
};

TEST_F(DriveInputTest, ThePadInTheDriveTabDrivesTheRobotAndReleaseStopsIt) {
  widgets::DrivePad& pad = input_->pad();
  ASSERT_TRUE(pad.isVisible());
  EXPECT_DOUBLE_EQ(pad.maxLinear(), session_->profile().limits.max_speed_mps);
  const QPoint centre(pad.width() / 2, pad.height() / 2);
  QTest::mousePress(&pad, Qt::LeftButton, {}, centre);
  QTest::mouseMove(&pad, centre - QPoint(0, pad.height()));  // full forward
  // Full deflection is clamped to the pad's circle; on a pad an odd number of pixels wide the
  // integer centre is half a pixel off the true one, so "straight up" leans by half a pixel over
  // 1.5 pad heights: the forward share is the cosine of that, within 1e-4 of one above 40 px.
  ASSERT_GT(pad.height(), 40);
  EXPECT_NEAR(session_->command().linear_mps, session_->profile().limits.max_speed_mps,
              1e-4 * session_->profile().limits.max_speed_mps);
  run(1.0);
  EXPECT_GT(pose().x, 0.05);
  QTest::mouseRelease(&pad, Qt::LeftButton, {}, centre - QPoint(0, pad.height()));
  EXPECT_DOUBLE_EQ(session_->command().linear_mps, 0.0);
  EXPECT_DOUBLE_EQ(session_->command().angular_radps, 0.0);
}

TEST_F(DriveInputTest, TheGamepadDrivesTheSessionRobotWithTheProfileLimits) {
  device_->state = stick(0.0, -1.0, true);  // full left: counter-clockwise
  input_->gamepad().pollOnce();
  EXPECT_NEAR(session_->command().angular_radps,
              0.5 * session_->profile().limits.max_turn_rate_radps, 1e-9);
  EXPECT_TRUE(input_->gamepadStatus().text().contains(QStringLiteral("Fake Pad")));
  run(1.0);
  EXPECT_GT(pose().theta, 0.1);
  device_->state = stick(0.0, -1.0, false);
  input_->gamepad().pollOnce();
  EXPECT_DOUBLE_EQ(session_->command().angular_radps, 0.0);
}

}  // namespace
}  // namespace irgs::gui
