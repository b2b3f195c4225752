// MAVLink signing from the GUI (issue 24, item 6): the connection dialog's choice is kept in the
// user's settings (file readable by the user only) and applied to the link, so the window drives
// an irgs-robot that refuses unsigned commands. Offscreen, in-process, irgs-robot over TCP.

#include <gtest/gtest.h>

#include <QFile>
#include <QSettings>
#include <QTest>

#include "app/gui/app_settings.hpp"
#include "app/gui/link_controller.hpp"
#include "app/gui/link_ui.hpp"
#include "app/gui/main_window.hpp"
#include "app/gui/session_controller.hpp"
#include "app_test_support.hpp"
#include "child_process.hpp"
#include "comms/mavlink/signing_key.hpp"
#include "tests/e2e/main_window_fixture.hpp"
#include "widgets/console/console_widget.hpp"
#include "widgets/link/link_health_panel.hpp"

namespace irgs::gui {
namespace {

namespace mav = comms::mavlink;
constexpr int kConnectTimeout_ms = 60000;  // a loaded 2-core machine

class LinkSigningTest : public test::MainWindowFixture {
 protected:
  void SetUp() override {
    openWindow(test::squareRoom());
    session_->start();
  }
  void TearDown() override {
    window_.reset();
    session_.reset();
    robot_.reset();
  }

  // irgs-robot as a TCP server that refuses what is not signed with `key`; returns its URL.
  QString startSignedRobot(const mav::SigningKey& key) {
    const QString key_file = dir_.filePath(QStringLiteral("robot.key"));
    EXPECT_EQ(mav::saveSigningKeyFile(key_file.toStdString(), key), "");
    robot_ = std::make_unique<irgs::test::ChildProcess>(std::vector<std::string>{
        IRGS_ROBOT_EXE, "--tcp", "0", "--seed", "5", "--signing-key", key_file.toStdString()});
    const auto deadline = irgs::test::Clock::now() + std::chrono::seconds(30);
    while (auto line = robot_->readLine(deadline)) {
      if (line->rfind("tcp ", 0) == 0)
        return QStringLiteral("tcp://127.0.0.1:%1").arg(QString::fromStdString(line->substr(4)));
    }
    ADD_FAILURE() << "irgs-robot announced no TCP port";
    return {};
  }
  LinkUi& link() const { return window_->linkUi(); }

  // Turns the robot through the session; true when its odometry heading changed within
  // `wait_ms` (once the link is up and telemetry flows).
  bool turns(int wait_ms) {
    if (!QTest::qWaitFor(
            [&] {
              return link().controller().health().state == widgets::LinkHealthState::kConnected;
            },
            kConnectTimeout_ms) ||
        !QTest::qWaitFor([&] { return link().controller().rates().samples > 20; },
                         kConnectTimeout_ms))
      return false;
    const double theta0 = session_->latestSample()->odometry_pose.theta;
    session_->drive(0.0, 0.8);
    const bool turned = QTest::qWaitFor(
        [&] {
          return std::abs(wrapAngle(session_->latestSample()->odometry_pose.theta - theta0)) > 0.3;
        },
        wait_ms);
    session_->stopRobot();
    return turned;
  }

  std::unique_ptr<irgs::test::ChildProcess> robot_;
};

TEST_F(LinkSigningTest, TheDialogOffersSigningAndConnectKeepsTheChoiceInTheUsersSettingsOnly) {
  const mav::SigningKey key = mav::randomSigningKey();
  const QString url = startSignedRobot(key);
  ASSERT_FALSE(url.isEmpty());
  const QString key_text = QString::fromStdString(mav::signingKeyText(key));
  link().setDialogRunner([&](widgets::ConnectionDialogOptions options) -> std::optional<QString> {
    EXPECT_TRUE(options.signing_tools.usable());
    EXPECT_EQ(options.signing, widgets::SigningChoice{});  // nothing saved yet
    EXPECT_EQ(options.signing_tools.fingerprint(key_text),
              QString::fromStdString(mav::signingKeyFingerprint(key)));
    options.save_signing(widgets::SigningChoice{true, key_text});  // what Connect does
    return url;
  });
  ASSERT_TRUE(link().chooseAndConnect());
  EXPECT_TRUE(settings_->value(QString::fromLatin1(settings_key::kLinkSigning)).toBool());
  EXPECT_EQ(settings_->value(QString::fromLatin1(settings_key::kLinkSigningKey)).toString(),
            key_text);
  EXPECT_EQ(QFile::permissions(settings_->fileName()) &
                (QFileDevice::ReadGroup | QFileDevice::ReadOther | QFileDevice::WriteGroup |
                 QFileDevice::WriteOther),
            QFileDevice::Permissions());
  EXPECT_TRUE(turns(kConnectTimeout_ms)) << "the signed link did not drive the robot";
  EXPECT_TRUE(QTest::qWaitFor(
      [&] {
        return window_->console().visibleText().contains(
            QStringLiteral("MAVLink signing on, key ") +
            QString::fromStdString(mav::signingKeyFingerprint(key)));
      },
      5000));
}

TEST_F(LinkSigningTest, WithSigningOffTheKeyedRobotIgnoresTheWindow) {
  const mav::SigningKey key = mav::randomSigningKey();
  const QString url = startSignedRobot(key);
  ASSERT_FALSE(url.isEmpty());
  // A key saved but switched off: the link is unsigned, and the robot moves nothing for it.
  link().saveSigningChoice(
      widgets::SigningChoice{false, QString::fromStdString(mav::signingKeyText(key))});
  ASSERT_EQ(link().connectTo(url), QString());
  EXPECT_FALSE(turns(3000)) << "an unsigned link drove a robot that has a key";
  // The robot says why (its signed STATUSTEXT is shown unverified).
  EXPECT_TRUE(QTest::qWaitFor(
      [&] {
        return window_->console().visibleText().contains(QStringLiteral("unsigned/bad signature"));
      },
      5000));
}

}  // namespace
}  // namespace irgs::gui
