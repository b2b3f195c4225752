#include "widgets/link/connection_dialog.hpp"

#include <gtest/gtest.h>

#include <QComboBox>
#include <QLabel>
#include <QLineEdit>
#include <QRadioButton>
#include <QSignalSpy>
#include <QToolButton>
#include <QtTest/QTest>

namespace irgs::widgets {
namespace {

std::vector<LinkPortEntry> twoPorts() {
  return {{QStringLiteral("/dev/ttyUSB0"), QStringLiteral("FT232R USB UART (FTDI)"),
           QStringLiteral("USB serial")},
          {QStringLiteral("/dev/rfcomm0"), QStringLiteral("HC-05 98:D3:31:F5:2A:11"),
           QStringLiteral("Bluetooth")}};
}

TEST(ConnectionDialog, ListsPortsWithTheirNamesAndBuildsASerialUrlFromPortAndBaud) {
  ConnectionDialogOptions options;
  options.ports = twoPorts();
  ConnectionDialog dialog(options);
  auto* combo = dialog.findChild<QComboBox*>(QStringLiteral("linkPort"));
  ASSERT_NE(combo, nullptr);
  ASSERT_EQ(combo->count(), 2);
  EXPECT_TRUE(combo->itemText(1).contains(QStringLiteral("HC-05")));
  EXPECT_TRUE(combo->itemText(1).contains(QStringLiteral("Bluetooth")));
  EXPECT_TRUE(dialog.usingPort());  // ports listed and no last URL: the picker
  EXPECT_EQ(dialog.url(), QStringLiteral("serial:///dev/ttyUSB0?baud=115200"));
  dialog.selectPort(QStringLiteral("/dev/rfcomm0"));
  dialog.setBaud(38400);
  EXPECT_EQ(dialog.url(), QStringLiteral("serial:///dev/rfcomm0?baud=38400"));
  EXPECT_EQ(dialog.protocol(), QStringLiteral("MAVLink 2"));
}

TEST(ConnectionDialog, LastSerialUrlOnAListedPortSelectsThatPortAndBaud) {
  ConnectionDialogOptions options;
  options.ports = twoPorts();
  options.initial_url = QStringLiteral("serial:///dev/rfcomm0?baud=9600");
  ConnectionDialog dialog(options);
  EXPECT_TRUE(dialog.usingPort());
  EXPECT_EQ(dialog.url(), options.initial_url);
}

TEST(ConnectionDialog, LastUrlOfAnUnlistedDeviceIsShownInTheUrlField) {
  ConnectionDialogOptions options;
  options.ports = twoPorts();
  options.initial_url = QStringLiteral("tcp://192.168.4.1:5760");
  ConnectionDialog dialog(options);
  EXPECT_FALSE(dialog.usingPort());
  EXPECT_EQ(dialog.url(), options.initial_url);
  EXPECT_EQ(dialog.findChild<QLineEdit*>(QStringLiteral("linkUrl"))->text(), options.initial_url);
}

TEST(ConnectionDialog, WithoutPortsOnlyTheUrlFieldIsUsable) {
  ConnectionDialog dialog(ConnectionDialogOptions{});
  EXPECT_FALSE(dialog.usingPort());
  EXPECT_FALSE(dialog.findChild<QRadioButton*>(QStringLiteral("linkUsePort"))->isEnabled());
  dialog.setUsePort(true);  // refused: nothing to pick
  EXPECT_FALSE(dialog.usingPort());
  dialog.setUrlText(QStringLiteral("  udp://:14550  "));
  EXPECT_EQ(dialog.url(), QStringLiteral("udp://:14550"));
}

TEST(ConnectionDialog, AnInvalidUrlKeepsTheDialogOpenAndShowsTheReason) {
  ConnectionDialogOptions options;
  int checks = 0;
  options.validate = [&checks](const QString& url) {
    ++checks;
    return url.startsWith(QStringLiteral("tcp://"))
               ? QString()
               : QStringLiteral("unknown scheme in '%1'").arg(url);
  };
  ConnectionDialog dialog(options);
  QSignalSpy accepted(&dialog, &QDialog::accepted);
  dialog.setUrlText(QStringLiteral("ftp://robot"));
  dialog.accept();
  EXPECT_EQ(accepted.count(), 0);
  EXPECT_TRUE(dialog.errorText().contains(QStringLiteral("unknown scheme")));
  dialog.setUrlText(QStringLiteral("tcp://robot:5760"));
  EXPECT_TRUE(dialog.errorText().isEmpty());  // editing clears the old reason
  dialog.accept();
  EXPECT_EQ(accepted.count(), 1);
  EXPECT_EQ(checks, 2);
}

TEST(ConnectionDialog, AnEmptyUrlIsRefusedWithoutAskingTheValidator) {
  ConnectionDialogOptions options;
  bool asked = false;
  options.validate = [&asked](const QString&) {
    asked = true;
    return QString();
  };
  ConnectionDialog dialog(options);
  QSignalSpy accepted(&dialog, &QDialog::accepted);
  dialog.accept();
  EXPECT_EQ(accepted.count(), 0);
  EXPECT_FALSE(asked);
  EXPECT_FALSE(dialog.errorText().isEmpty());
}

TEST(ConnectionDialog, RefreshListsThePortsAgainKeepingTheSelection) {
  ConnectionDialogOptions options;
  options.ports = twoPorts();
  int scans = 0;
  options.rescan = [&scans] {
    ++scans;
    auto ports = twoPorts();
    ports.push_back(
        {QStringLiteral("/dev/ttyACM0"), QStringLiteral("Arduino Uno"), QStringLiteral("USB ACM")});
    return ports;
  };
  ConnectionDialog dialog(options);
  dialog.selectPort(QStringLiteral("/dev/rfcomm0"));
  auto* refresh = dialog.findChild<QToolButton*>(QStringLiteral("linkRefreshPorts"));
  ASSERT_NE(refresh, nullptr);
  QTest::mouseClick(refresh, Qt::LeftButton);
  EXPECT_EQ(scans, 1);
  EXPECT_EQ(dialog.findChild<QComboBox*>(QStringLiteral("linkPort"))->count(), 3);
  EXPECT_EQ(dialog.url(), QStringLiteral("serial:///dev/rfcomm0?baud=115200"));
}

TEST(ConnectionDialog, AnUnusualBaudFromTheLastUrlGetsItsOwnEntry) {
  ConnectionDialogOptions options;
  options.ports = twoPorts();
  options.initial_url = QStringLiteral("serial:///dev/ttyUSB0?baud=250000");
  ConnectionDialog dialog(options);
  EXPECT_EQ(dialog.url(), QStringLiteral("serial:///dev/ttyUSB0?baud=250000"));
}

}  // namespace
}  // namespace irgs::widgets
