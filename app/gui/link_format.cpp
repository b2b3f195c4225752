#include "app/gui/link_format.hpp"

#include "comms/link/link_url.hpp"

namespace irgs::gui {

widgets::LinkHealthState toHealthState(comms::LinkState state) {
  switch (state) {
    case comms::LinkState::kDisconnected:
      return widgets::LinkHealthState::kDisconnected;
    case comms::LinkState::kConnecting:
      return widgets::LinkHealthState::kConnecting;
    case comms::LinkState::kConnected:
      return widgets::LinkHealthState::kConnected;
    case comms::LinkState::kLost:
      return widgets::LinkHealthState::kLost;
  }
  return widgets::LinkHealthState::kDisconnected;
}

widgets::LinkHealth toLinkHealth(const comms::LinkStats& stats, const QString& link) {
  widgets::LinkHealth health;
  health.state = toHealthState(stats.state);
  health.link = link;
  health.rx_bytes_per_s = stats.rx_bytes_per_s;
  health.tx_bytes_per_s = stats.tx_bytes_per_s;
  health.rx_messages_per_s = stats.rx_messages_per_s;
  health.tx_messages_per_s = stats.tx_messages_per_s;
  health.tx_budget_bytes_per_s = stats.tx_budget_bytes_per_s;
  health.crc_errors = stats.crc_errors;
  health.sequence_errors = stats.sequence_errors;
  health.other_errors = stats.other_errors;
  health.loss_percent = stats.loss_percent;
  health.rtt_s = stats.rtt_s;
  health.since_heartbeat_s = stats.since_heartbeat_s;
  health.link_losses = stats.link_losses;
  health.reconnect_attempts = stats.reconnect_attempts;
  health.peer_system_id = stats.peer_system_id;
  return health;
}

widgets::LinkPortEntry toPortEntry(const comms::SerialPortInfo& port) {
  widgets::LinkPortEntry entry;
  entry.path = QString::fromStdString(port.path);
  entry.description = QString::fromStdString(port.description);
  switch (port.kind) {
    case comms::SerialPortKind::kUsbSerial:
      entry.kind = QStringLiteral("USB serial");
      break;
    case comms::SerialPortKind::kUsbAcm:
      entry.kind = QStringLiteral("USB ACM");
      break;
    case comms::SerialPortKind::kOnboard:
      entry.kind = QStringLiteral("on-board UART");
      break;
    case comms::SerialPortKind::kBluetooth:
      entry.kind = QStringLiteral("Bluetooth");
      break;
  }
  return entry;
}

EventLevel levelOfSeverity(std::uint8_t severity) {
  if (severity <= 3)
    return EventLevel::kError;
  if (severity == 4)
    return EventLevel::kWarning;
  return EventLevel::kInfo;
}

QString formatLinkEvent(const comms::LinkEvent& event) {
  const QString text = QString::fromStdString(event.text);
  return event.kind == comms::LinkEventKind::kStatusText ? QStringLiteral("Robot: %1").arg(text)
                                                         : QStringLiteral("Link: %1").arg(text);
}

QString validateLinkUrl(const QString& url) {
  const comms::LinkUrlResult parsed = comms::parseLinkUrl(url.trimmed().toStdString());
  return parsed.url ? QString() : QString::fromStdString(parsed.error);
}

}  // namespace irgs::gui
