#include "widgets/link/link_health_panel.hpp"

#include <QFontDatabase>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QPushButton>
#include <QVBoxLayout>
#include <cmath>

namespace irgs::widgets {
namespace {

const QChar kZeroWidthSpace(0x200B);  // a line-break opportunity, invisible

QString rate(double bytes_per_s, double messages_per_s) {
  const QString bytes = bytes_per_s >= 1000.0
                            ? QStringLiteral("%1 kB/s").arg(bytes_per_s / 1000.0, 0, 'f', 1)
                            : QStringLiteral("%1 B/s").arg(bytes_per_s, 0, 'f', 0);
  return QStringLiteral("%1 · %2 msg/s").arg(bytes).arg(messages_per_s, 0, 'f', 0);
}

QString finiteOr(const std::optional<double>& value, const QString& format_ok, double scale,
                 int decimals) {
  if (!value || !std::isfinite(*value))
    return QStringLiteral("—");
  return format_ok.arg(*value * scale, 0, 'f', decimals);
}

}  // namespace

LinkHealthPanel::LinkHealthPanel(QWidget* parent) : QWidget(parent) {
  setObjectName(QStringLiteral("linkHealthPanel"));
  state_ = new QLabel(this);
  state_->setObjectName(QStringLiteral("linkState"));
  state_->setAlignment(Qt::AlignCenter);
  state_->setMinimumWidth(96);
  connect_button_ = new QPushButton(tr("Connect…"), this);
  connect_button_->setObjectName(QStringLiteral("linkConnect"));
  connect_button_->setToolTip(tr("Choose the port or URL of the robot"));
  connect_button_->setFocusPolicy(Qt::NoFocus);
  disconnect_button_ = new QPushButton(tr("Disconnect"), this);
  disconnect_button_->setObjectName(QStringLiteral("linkDisconnect"));
  disconnect_button_->setToolTip(tr("Close the link and go back to the simulator"));
  disconnect_button_->setFocusPolicy(Qt::NoFocus);
  connect(connect_button_, &QPushButton::clicked, this, &LinkHealthPanel::connectRequested);
  connect(disconnect_button_, &QPushButton::clicked, this, &LinkHealthPanel::disconnectRequested);

  auto* top = new QHBoxLayout;
  top->addWidget(state_);
  top->addStretch(1);
  top->addWidget(connect_button_);
  top->addWidget(disconnect_button_);

  form_ = new QFormLayout;
  form_->setHorizontalSpacing(10);
  form_->setVerticalSpacing(2);
  form_->setLabelAlignment(Qt::AlignRight);
  link_ = addField(tr("Link"), "linkUrl", tr("The port or URL of the robot link"));
  link_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  link_->setWordWrap(true);
  // Wrap to the column instead of widening it (long device paths and URLs).
  link_->setSizePolicy(QSizePolicy::Ignored, QSizePolicy::Preferred);
  rx_ = addField(tr("Received"), "linkRx",
                 tr("Bytes and MAVLink messages per second from the robot"));
  tx_ = addField(tr("Sent"), "linkTx", tr("Bytes and MAVLink messages per second to the robot"));
  tx_budget_ = addSecondField(tx_, "linkTxBudget",
                              tr("Share of what the link carries towards the robot (baud / 10 "
                                 "bytes per second; the URL's baud). Commands should stay well "
                                 "under half of it"));
  // Two values per row where they belong together: the side column is narrow.
  errors_ = addField(tr("Errors"), "linkErrors",
                     tr("Frames with a bad checksum (CRC), frames missing by sequence number, "
                        "and other rejected frames (length, unknown id, signature)"));
  loss_ = addSecondField(errors_, "linkLoss",
                         tr("Frames missing / frames expected, over the last seconds"));
  rtt_ = addField(tr("Round trip"), "linkRtt", tr("TIMESYNC round-trip time"));
  heartbeat_ = addSecondField(rtt_, "linkHeartbeat",
                              tr("Age of the robot's last heartbeat (sent once per second); the "
                                 "link counts as lost after 1.5 s"));
  reconnects_ = addField(tr("Reconnects"), "linkReconnects",
                         tr("Reopen attempts and link losses since connecting"));

  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(6, 4, 6, 4);
  layout->setSpacing(4);
  layout->addLayout(top);
  layout->addLayout(form_);
  setHealth(LinkHealth{});
}

QLabel* LinkHealthPanel::addField(const QString& label, const char* name, const QString& tooltip) {
  auto* value = new QLabel(this);
  value->setObjectName(QLatin1String(name));
  value->setToolTip(tooltip);
  value->setFont(QFontDatabase::systemFont(QFontDatabase::FixedFont));
  auto* caption = new QLabel(label, this);
  caption->setToolTip(tooltip);
  form_->addRow(caption, value);
  return value;
}

QLabel* LinkHealthPanel::addSecondField(QLabel* first, const char* name, const QString& tooltip) {
  // Re-seat `first` in a row layout with the new label after it.
  int row = -1;
  QFormLayout::ItemRole role{};
  form_->getWidgetPosition(first, &row, &role);
  auto* value = new QLabel(this);
  value->setObjectName(QLatin1String(name));
  value->setToolTip(tooltip);
  value->setFont(first->font());
  auto* pair = new QHBoxLayout;
  pair->setSpacing(16);
  form_->removeWidget(first);
  pair->addWidget(first);
  pair->addWidget(value);
  pair->addStretch(1);
  form_->setLayout(row, QFormLayout::FieldRole, pair);
  return value;
}

QString LinkHealthPanel::stateText(LinkHealthState state) {
  switch (state) {
    case LinkHealthState::kDisconnected:
      return tr("disconnected");
    case LinkHealthState::kConnecting:
      return tr("connecting");
    case LinkHealthState::kConnected:
      return tr("connected");
    case LinkHealthState::kLost:
      return tr("lost");
  }
  return {};
}

QString LinkHealthPanel::stateColour(LinkHealthState state) {
  switch (state) {
    case LinkHealthState::kDisconnected:
      return QStringLiteral("#78909c");
    case LinkHealthState::kConnecting:
      return QStringLiteral("#f9a825");
    case LinkHealthState::kConnected:
      return QStringLiteral("#2e7d32");
    case LinkHealthState::kLost:
      return QStringLiteral("#c62828");
  }
  return QStringLiteral("#78909c");
}

void LinkHealthPanel::setHealth(const LinkHealth& health) {
  health_ = health;
  state_->setText(stateText(health.state).toUpper());
  state_->setStyleSheet(QStringLiteral("QLabel { background: %1; color: white; font-weight: bold;"
                                       " border-radius: 4px; padding: 2px 8px; }")
                            .arg(stateColour(health.state)));
  const bool active = health.state != LinkHealthState::kDisconnected;
  disconnect_button_->setEnabled(active);
  // A URL has no spaces: allow breaks after its separators so it wraps in the narrow column.
  QString link = health.link.isEmpty() ? QStringLiteral("—") : health.link;
  if (health.peer_system_id != 0)
    link += tr(" (system %1)").arg(health.peer_system_id);
  link_->setText(link);
  QString breakable = link;
  for (const QChar separator : {QLatin1Char('/'), QLatin1Char('?'), QLatin1Char('&')})
    breakable.replace(separator, QString(separator) + kZeroWidthSpace);
  link_->setTextFormat(Qt::PlainText);
  link_->setText(breakable);
  link_->setToolTip(link);
  rx_->setText(rate(health.rx_bytes_per_s, health.rx_messages_per_s));
  tx_->setText(rate(health.tx_bytes_per_s, health.tx_messages_per_s));
  const std::optional<double>& budget = health.tx_budget_bytes_per_s;
  const bool known = budget && std::isfinite(*budget) && *budget > 0.0;
  const double share = known ? health.tx_bytes_per_s / *budget : 0.0;
  tx_budget_->setText(
      known ? tr("%1 % of %2 B/s").arg(share * 100.0, 0, 'f', 0).arg(*budget, 0, 'f', 0)
            : tr("budget unknown"));
  tx_budget_->setStyleSheet(share > kTxBudgetWarnShare ? QStringLiteral("color: #c62828;")
                                                       : QString());
  errors_->setText(QStringLiteral("CRC %1 · seq %2 · other %3")
                       .arg(health.crc_errors)
                       .arg(health.sequence_errors)
                       .arg(health.other_errors));
  const double loss = std::isfinite(health.loss_percent) ? health.loss_percent : 0.0;
  loss_->setText(tr("loss %1 %").arg(loss, 0, 'f', 1));
  loss_->setStyleSheet(loss >= 5.0 ? QStringLiteral("color: #c62828;") : QString());
  rtt_->setText(finiteOr(health.rtt_s, QStringLiteral("%1 ms"), 1000.0, 1));
  heartbeat_->setText(
      tr("heartbeat %1").arg(finiteOr(health.since_heartbeat_s, tr("%1 s ago"), 1.0, 1)));
  const bool stale = health.since_heartbeat_s && *health.since_heartbeat_s > kHeartbeatWarn_s;
  heartbeat_->setStyleSheet(stale ? QStringLiteral("color: #c62828;") : QString());
  reconnects_->setText(
      tr("%1 attempts · %2 losses").arg(health.reconnect_attempts).arg(health.link_losses));
}

QString LinkHealthPanel::fieldText(const QString& name) const {
  const auto* label = findChild<QLabel*>(name);
  return label != nullptr ? label->text().remove(kZeroWidthSpace) : QString();
}

}  // namespace irgs::widgets
