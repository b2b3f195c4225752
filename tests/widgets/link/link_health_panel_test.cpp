#include "widgets/link/link_health_panel.hpp"

#include <gtest/gtest.h>

#include <QLabel>
#include <QPushButton>
#include <QSignalSpy>
#include <QtTest/QTest>
#include <cmath>

namespace irgs::widgets {
namespace {

TEST(LinkHealthPanel, ShowsRatesErrorsLossRttHeartbeatAndReconnects) {
  LinkHealthPanel panel;
  LinkHealth health;
  health.state = LinkHealthState::kConnected;
  health.link = QStringLiteral("serial:///dev/rfcomm0?baud=38400");
  health.rx_bytes_per_s = 3456.0;
  health.rx_messages_per_s = 181.0;
  health.tx_bytes_per_s = 120.0;
  health.tx_messages_per_s = 12.0;
  health.crc_errors = 3;
  health.sequence_errors = 7;
  health.other_errors = 1;
  health.loss_percent = 2.24;
  health.rtt_s = 0.0123;
  health.since_heartbeat_s = 0.4;
  health.reconnect_attempts = 4;
  health.link_losses = 2;
  health.peer_system_id = 1;
  panel.setHealth(health);
  EXPECT_EQ(panel.fieldText(QStringLiteral("linkState")), QStringLiteral("CONNECTED"));
  EXPECT_TRUE(panel.fieldText(QStringLiteral("linkUrl")).contains(health.link));
  EXPECT_TRUE(panel.fieldText(QStringLiteral("linkUrl")).contains(QStringLiteral("system 1")));
  EXPECT_EQ(panel.fieldText(QStringLiteral("linkRx")), QStringLiteral("3.5 kB/s · 181 msg/s"));
  EXPECT_EQ(panel.fieldText(QStringLiteral("linkTx")), QStringLiteral("120 B/s · 12 msg/s"));
  EXPECT_EQ(panel.fieldText(QStringLiteral("linkTxBudget")), QStringLiteral("budget unknown"));
  EXPECT_EQ(panel.fieldText(QStringLiteral("linkErrors")),
            QStringLiteral("CRC 3 · seq 7 · other 1"));
  EXPECT_EQ(panel.fieldText(QStringLiteral("linkLoss")), QStringLiteral("loss 2.2 %"));
  EXPECT_EQ(panel.fieldText(QStringLiteral("linkRtt")), QStringLiteral("12.3 ms"));
  EXPECT_EQ(panel.fieldText(QStringLiteral("linkHeartbeat")),
            QStringLiteral("heartbeat 0.4 s ago"));
  EXPECT_EQ(panel.fieldText(QStringLiteral("linkReconnects")),
            QStringLiteral("4 attempts · 2 losses"));
}

TEST(LinkHealthPanel, ShowsWhatIsSentAgainstTheLinksByteBudgetAndWarnsAboveHalf) {
  LinkHealthPanel panel;
  LinkHealth health;
  health.state = LinkHealthState::kConnected;
  health.tx_bytes_per_s = 90.0;
  health.tx_budget_bytes_per_s = 960.0;  // 9600 baud
  panel.setHealth(health);
  auto* budget = panel.findChild<QLabel*>(QStringLiteral("linkTxBudget"));
  ASSERT_NE(budget, nullptr);
  EXPECT_EQ(panel.fieldText(QStringLiteral("linkTxBudget")), QStringLiteral("9 % of 960 B/s"));
  EXPECT_TRUE(budget->styleSheet().isEmpty());
  health.tx_bytes_per_s = 8500.0;  // the flood of issue 24 on a 9600-baud link
  panel.setHealth(health);
  EXPECT_EQ(panel.fieldText(QStringLiteral("linkTxBudget")), QStringLiteral("885 % of 960 B/s"));
  EXPECT_FALSE(budget->styleSheet().isEmpty());
}

TEST(LinkHealthPanel, MissingOrNonFiniteValuesShowAsDashesNotNumbers) {
  LinkHealthPanel panel;
  LinkHealth health;
  health.state = LinkHealthState::kConnecting;
  health.rtt_s = std::nan("");
  health.loss_percent = INFINITY;
  panel.setHealth(health);
  EXPECT_EQ(panel.fieldText(QStringLiteral("linkState")), QStringLiteral("CONNECTING"));
  EXPECT_EQ(panel.fieldText(QStringLiteral("linkRtt")), QStringLiteral("—"));
  EXPECT_EQ(panel.fieldText(QStringLiteral("linkHeartbeat")), QStringLiteral("heartbeat —"));
  EXPECT_EQ(panel.fieldText(QStringLiteral("linkLoss")), QStringLiteral("loss 0.0 %"));
  EXPECT_EQ(panel.fieldText(QStringLiteral("linkUrl")), QStringLiteral("—"));
}

TEST(LinkHealthPanel, EveryStateHasItsOwnWordAndColour) {
  const LinkHealthState states[] = {LinkHealthState::kDisconnected, LinkHealthState::kConnecting,
                                    LinkHealthState::kConnected, LinkHealthState::kLost};
  QStringList words, colours;
  for (LinkHealthState state : states) {
    words << LinkHealthPanel::stateText(state);
    colours << LinkHealthPanel::stateColour(state);
  }
  words.removeDuplicates();
  colours.removeDuplicates();
  EXPECT_EQ(words.size(), 4);
  EXPECT_EQ(colours.size(), 4);
}

TEST(LinkHealthPanel, ButtonsAskToConnectAndDisconnectOnlyWhileALinkIsActive) {
  LinkHealthPanel panel;
  QSignalSpy connect_spy(&panel, &LinkHealthPanel::connectRequested);
  QSignalSpy disconnect_spy(&panel, &LinkHealthPanel::disconnectRequested);
  auto* connect_button = panel.findChild<QPushButton*>(QStringLiteral("linkConnect"));
  auto* disconnect_button = panel.findChild<QPushButton*>(QStringLiteral("linkDisconnect"));
  ASSERT_NE(connect_button, nullptr);
  ASSERT_NE(disconnect_button, nullptr);
  EXPECT_FALSE(disconnect_button->isEnabled());
  LinkHealth health;
  health.state = LinkHealthState::kLost;
  panel.setHealth(health);
  EXPECT_TRUE(disconnect_button->isEnabled());
  QTest::mouseClick(connect_button, Qt::LeftButton);
  QTest::mouseClick(disconnect_button, Qt::LeftButton);
  EXPECT_EQ(connect_spy.count(), 1);
  EXPECT_EQ(disconnect_spy.count(), 1);
}

}  // namespace
}  // namespace irgs::widgets
