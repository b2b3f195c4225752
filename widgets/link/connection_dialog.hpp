#pragma once
// The robot-link connection dialog: pick a serial / Bluetooth port (listed by the application,
// with names) and a baud rate, or type a link URL (serial://, tcp://, udp://), and a protocol;
// and MAVLink signing (SigningKeyBox) when the application supplies the key tools.
// Widgets never see comms: ports come in as plain values and the URL is checked by a function
// the application passes in.

#include <QDialog>
#include <QString>
#include <QStringList>
#include <functional>
#include <vector>

#include "widgets/link/signing_key_box.hpp"

class QButtonGroup;
class QComboBox;
class QDialogButtonBox;
class QLabel;
class QLineEdit;
class QRadioButton;
class QToolButton;

namespace irgs::widgets {

// One port of the picker.
struct LinkPortEntry {
  QString path;         // device node, e.g. "/dev/ttyUSB0" or "/dev/rfcomm0"
  QString description;  // one line: product / Bluetooth name, e.g. "FT232R USB UART (FTDI)"
  QString kind;         // short kind label: "USB serial", "USB ACM", "On-board", "Bluetooth"
};

struct ConnectionDialogOptions {
  std::vector<LinkPortEntry> ports;
  // Lists the ports again (the Refresh button); empty: no Refresh button.
  std::function<std::vector<LinkPortEntry>()> rescan;
  QStringList protocols{QStringLiteral("MAVLink 2")};
  // Preselected URL (the last one used). A serial URL on a listed port selects that port.
  QString initial_url;
  // Checks a URL: an empty string when it is usable, else the reason (shown in the dialog).
  std::function<QString(const QString& url)> validate;
  // MAVLink signing: shown when the tools are usable, starting from `signing`; on Connect the
  // choice is handed to `save_signing` (the application keeps it in the user's settings).
  SigningKeyTools signing_tools;
  SigningChoice signing;
  std::function<void(const SigningChoice& choice)> save_signing;
};

class ConnectionDialog : public QDialog {
  Q_OBJECT

 public:
  // Baud rates offered for serial ports (HC-05 Bluetooth modules default to 9600 / 38400).
  static const std::vector<int>& baudRates();
  static constexpr int kDefaultBaud = 115200;

  explicit ConnectionDialog(ConnectionDialogOptions options, QWidget* parent = nullptr);

  // The URL the dialog currently describes (port + baud, or the typed text, trimmed).
  QString url() const;
  QString protocol() const;
  bool usingPort() const;
  // The signing switch and key (options.signing unchanged when the section is not shown).
  SigningChoice signing() const;
  SigningKeyBox* signingBox() const { return signing_box_; }
  // The validation message of the last Connect attempt (empty when none or accepted).
  QString errorText() const;

  // Programmatic selection (tests, the last URL): these do what the user would.
  void setPortList(const std::vector<LinkPortEntry>& ports);
  void selectPort(const QString& path);
  void setBaud(int baud);
  void setUrlText(const QString& text);
  void setUsePort(bool use_port);

  // "serial:///dev/ttyUSB0?baud=115200".
  static QString serialUrl(const QString& path, int baud);

 public slots:
  void accept() override;  // validates first; stays open showing the reason when invalid

 private:
  void rescanPorts();
  void updateEnabled();
  void updatePreview();

  ConnectionDialogOptions options_;
  QRadioButton* port_radio_ = nullptr;
  QRadioButton* url_radio_ = nullptr;
  QButtonGroup* source_group_ = nullptr;
  QComboBox* port_combo_ = nullptr;
  QToolButton* refresh_button_ = nullptr;
  QComboBox* baud_combo_ = nullptr;
  QLineEdit* url_edit_ = nullptr;
  QComboBox* protocol_combo_ = nullptr;
  QLabel* preview_ = nullptr;
  QLabel* error_ = nullptr;
  SigningKeyBox* signing_box_ = nullptr;  // null: no signing tools
  QDialogButtonBox* buttons_ = nullptr;
};

}  // namespace irgs::widgets
