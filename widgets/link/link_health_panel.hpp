#pragma once
// The link-health panel: connection state, traffic rates, decoder errors, loss, round-trip time,
// heartbeat age and reconnections of the robot link. Fed with a plain widget-level value (the
// application converts its link statistics; widgets never include comms).

#include <QString>
#include <QWidget>
#include <cstdint>
#include <optional>

class QFormLayout;
class QLabel;
class QPushButton;

namespace irgs::widgets {

enum class LinkHealthState { kDisconnected, kConnecting, kConnected, kLost };

struct LinkHealth {
  LinkHealthState state = LinkHealthState::kDisconnected;
  QString link;  // what we are connected to, e.g. "serial:///dev/rfcomm0?baud=38400"
  double rx_bytes_per_s = 0.0;
  double tx_bytes_per_s = 0.0;
  double rx_messages_per_s = 0.0;
  double tx_messages_per_s = 0.0;
  std::optional<double> tx_budget_bytes_per_s;  // baud / 10 of the link; empty: unknown
  std::uint64_t crc_errors = 0;
  std::uint64_t sequence_errors = 0;  // frames missing (sequence gaps)
  std::uint64_t other_errors = 0;     // bad length, unknown id, signature ...
  double loss_percent = 0.0;
  std::optional<double> rtt_s;              // last TIMESYNC round trip
  std::optional<double> since_heartbeat_s;  // age of the robot's last heartbeat
  std::uint32_t link_losses = 0;
  std::uint32_t reconnect_attempts = 0;
  std::uint8_t peer_system_id = 0;  // 0: no heartbeat yet
};

class LinkHealthPanel : public QWidget {
  Q_OBJECT

 public:
  // A heartbeat older than this is shown as a warning (the robot sends one per second).
  static constexpr double kHeartbeatWarn_s = 1.2;
  // Sent bytes above this share of the link's budget are shown as a warning.
  static constexpr double kTxBudgetWarnShare = 0.5;

  explicit LinkHealthPanel(QWidget* parent = nullptr);

  void setHealth(const LinkHealth& health);
  const LinkHealth& health() const { return health_; }

  // The one-word state as shown ("connected", "lost" ...), also for status bars.
  static QString stateText(LinkHealthState state);
  // Background colour of the state badge.
  static QString stateColour(LinkHealthState state);
  // The plain text of a field by its object name (tests): "linkRx", "linkRtt" ...
  QString fieldText(const QString& name) const;

 signals:
  void connectRequested();     // "Connect…": open the connection dialog
  void disconnectRequested();  // "Disconnect": back to the simulator

 private:
  QLabel* addField(const QString& label, const char* name, const QString& tooltip);
  QLabel* addSecondField(QLabel* first, const char* name, const QString& tooltip);

  LinkHealth health_;
  QLabel* state_ = nullptr;
  QLabel* link_ = nullptr;
  QLabel* rx_ = nullptr;
  QLabel* tx_ = nullptr;
  QLabel* tx_budget_ = nullptr;
  QLabel* errors_ = nullptr;
  QLabel* loss_ = nullptr;
  QLabel* rtt_ = nullptr;
  QLabel* heartbeat_ = nullptr;
  QLabel* reconnects_ = nullptr;
  QPushButton* connect_button_ = nullptr;
  QPushButton* disconnect_button_ = nullptr;
  QFormLayout* form_ = nullptr;
};

}  // namespace irgs::widgets
