// Entry point of the widget tests: one QApplication on the offscreen platform for all tests.
// (Defining main here keeps GTest::gtest_main's main out of the link.)

#include <gtest/gtest.h>

#include <QApplication>

int main(int argc, char** argv) {
  // Honour an explicit choice (e.g. QT_QPA_PLATFORM=xcb to watch a test), default to offscreen.
  if (qEnvironmentVariableIsEmpty("QT_QPA_PLATFORM"))
    qputenv("QT_QPA_PLATFORM", "offscreen");
  ::testing::InitGoogleTest(&argc, argv);
  QApplication app(argc, argv);
  return RUN_ALL_TESTS();
}
