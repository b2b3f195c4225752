#pragma once
// The starting point of most offscreen GUI tests: the main window on a simulated thesis robot,
// with a fresh settings file in a temporary folder and a world loaded.

#include <gtest/gtest.h>

#include <QSettings>
#include <QTemporaryDir>
#include <memory>

#include "app/gui/main_window.hpp"
#include "tests/e2e/app_test_support.hpp"

namespace irgs::gui::test {

class MainWindowFixture : public ::testing::Test {
 protected:
  // Builds the session and the window (not shown) and loads `world` as "room.json".
  void openWindow(const WorldMap& world) {
    ensureApp();
    ASSERT_TRUE(dir_.isValid());
    settings_ = std::make_unique<QSettings>(dir_.filePath(QStringLiteral("settings.ini")),
                                            QSettings::IniFormat);
    session_ = std::make_unique<SessionController>(thesisRobot(), simulatedFactory());
    window_ = std::make_unique<MainWindow>(*session_, *settings_);
    session_->loadWorld(world, QStringLiteral("room.json"));
  }

  // Declared in destruction order's reverse: the window goes before the session it shows.
  QTemporaryDir dir_;
  std::unique_ptr<QSettings> settings_;
  std::unique_ptr<SessionController> session_;
  std::unique_ptr<MainWindow> window_;
};

}  // namespace irgs::gui::test
