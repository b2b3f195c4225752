// What the GUI shows of the link: comms statistics, ports and events converted for the widgets.

#include "app/gui/link_format.hpp"

#include <gtest/gtest.h>

namespace irgs::gui {
namespace {

TEST(LinkFormat, StatisticsBecomeTheHealthPanelValuesUnchanged) {
  comms::LinkStats stats;
  stats.state = comms::LinkState::kLost;
  stats.rx_bytes_per_s = 1234.5;
  stats.tx_messages_per_s = 11.0;
  stats.tx_budget_bytes_per_s = 960.0;
  stats.crc_errors = 4;
  stats.sequence_errors = 9;
  stats.other_errors = 2;
  stats.loss_percent = 3.5;
  stats.rtt_s = 0.02;
  stats.since_heartbeat_s = 1.7;
  stats.link_losses = 1;
  stats.reconnect_attempts = 3;
  stats.peer_system_id = 1;
  const widgets::LinkHealth health = toLinkHealth(stats, QStringLiteral("tcp://robot:5760"));
  EXPECT_EQ(health.state, widgets::LinkHealthState::kLost);
  EXPECT_EQ(health.link, QStringLiteral("tcp://robot:5760"));
  EXPECT_DOUBLE_EQ(health.rx_bytes_per_s, 1234.5);
  EXPECT_DOUBLE_EQ(health.tx_messages_per_s, 11.0);
  EXPECT_EQ(health.tx_budget_bytes_per_s, std::optional<double>(960.0));
  EXPECT_EQ(health.crc_errors, 4u);
  EXPECT_EQ(health.sequence_errors, 9u);
  EXPECT_EQ(health.other_errors, 2u);
  EXPECT_DOUBLE_EQ(health.loss_percent, 3.5);
  EXPECT_EQ(health.rtt_s, std::optional<double>(0.02));
  EXPECT_EQ(health.since_heartbeat_s, std::optional<double>(1.7));
  EXPECT_EQ(health.link_losses, 1u);
  EXPECT_EQ(health.reconnect_attempts, 3u);
  EXPECT_EQ(health.peer_system_id, 1);
}

TEST(LinkFormat, EveryLinkStateMapsToItsOwnHealthState) {
  EXPECT_EQ(toHealthState(comms::LinkState::kDisconnected),
            widgets::LinkHealthState::kDisconnected);
  EXPECT_EQ(toHealthState(comms::LinkState::kConnecting), widgets::LinkHealthState::kConnecting);
  EXPECT_EQ(toHealthState(comms::LinkState::kConnected), widgets::LinkHealthState::kConnected);
  EXPECT_EQ(toHealthState(comms::LinkState::kLost), widgets::LinkHealthState::kLost);
}

TEST(LinkFormat, SeveritiesMapToErrorWarningAndInfoLevels) {
  for (std::uint8_t severity = 0; severity <= 3; ++severity)
    EXPECT_EQ(levelOfSeverity(severity), EventLevel::kError) << int(severity);
  EXPECT_EQ(levelOfSeverity(4), EventLevel::kWarning);
  for (std::uint8_t severity = 5; severity <= 7; ++severity)
    EXPECT_EQ(levelOfSeverity(severity), EventLevel::kInfo) << int(severity);
  EXPECT_EQ(levelOfSeverity(200), EventLevel::kInfo);  // out of range: not an alarm
}

TEST(LinkFormat, StatusTextIsTheRobotSpeakingOtherEventsAreTheLink) {
  comms::LinkEvent status;
  status.kind = comms::LinkEventKind::kStatusText;
  status.text = "bumper pressed: stopping";
  EXPECT_EQ(formatLinkEvent(status), QStringLiteral("Robot: bumper pressed: stopping"));
  comms::LinkEvent lost;
  lost.kind = comms::LinkEventKind::kLinkLost;
  lost.text = "no heartbeat for 1.5 s";
  EXPECT_EQ(formatLinkEvent(lost), QStringLiteral("Link: no heartbeat for 1.5 s"));
}

TEST(LinkFormat, PortsKeepPathAndDescriptionAndNameTheirKind) {
  comms::SerialPortInfo port;
  port.path = "/dev/rfcomm0";
  port.kind = comms::SerialPortKind::kBluetooth;
  port.description = "HC-05 (98:D3:31:F5:2A:11, channel 1)";
  const widgets::LinkPortEntry entry = toPortEntry(port);
  EXPECT_EQ(entry.path, QStringLiteral("/dev/rfcomm0"));
  EXPECT_EQ(entry.description, QStringLiteral("HC-05 (98:D3:31:F5:2A:11, channel 1)"));
  EXPECT_EQ(entry.kind, QStringLiteral("Bluetooth"));
}

TEST(LinkFormat, UrlValidationExplainsBadUrlsAndAcceptsGoodOnes) {
  EXPECT_TRUE(validateLinkUrl(QStringLiteral("serial:///dev/ttyUSB0?baud=115200")).isEmpty());
  EXPECT_TRUE(validateLinkUrl(QStringLiteral(" tcp://127.0.0.1:5760 ")).isEmpty());
  EXPECT_FALSE(validateLinkUrl(QStringLiteral("ftp://robot")).isEmpty());
  EXPECT_FALSE(validateLinkUrl(QString()).isEmpty());
}

}  // namespace
}  // namespace irgs::gui
