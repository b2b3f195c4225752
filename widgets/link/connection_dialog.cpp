#include "widgets/link/connection_dialog.hpp"

#include <QButtonGroup>
#include <QComboBox>
#include <QDialogButtonBox>
#include <QFormLayout>
#include <QGridLayout>
#include <QGroupBox>
#include <QLabel>
#include <QLineEdit>
#include <QPushButton>
#include <QRadioButton>
#include <QRegularExpression>
#include <QStyle>
#include <QToolButton>
#include <QVBoxLayout>
#include <optional>

namespace irgs::widgets {
namespace {

constexpr int kPortId = 0;
constexpr int kUrlId = 1;

// The device and baud of a serial URL, to preselect a listed port (just enough parsing for
// that: the application's validator is the authority on URLs).
struct SerialParts {
  QString path;
  int baud = 0;
};
std::optional<SerialParts> serialParts(const QString& url) {
  static const QRegularExpression kSerial(QStringLiteral("^serial://(/[^?]+)(?:\\?(.*))?$"));
  const auto match = kSerial.match(url.trimmed());
  if (!match.hasMatch())
    return std::nullopt;
  SerialParts parts;
  parts.path = match.captured(1);
  for (const QString& item : match.captured(2).split(QLatin1Char('&'), Qt::SkipEmptyParts)) {
    if (item.startsWith(QStringLiteral("baud=")))
      parts.baud = item.mid(5).toInt();
  }
  return parts;
}

QString portLabel(const LinkPortEntry& port) {
  QString label = port.path;
  if (!port.description.isEmpty())
    label += QStringLiteral(" — ") + port.description;
  if (!port.kind.isEmpty())
    label += QStringLiteral(" [%1]").arg(port.kind);
  return label;
}

}  // namespace

const std::vector<int>& ConnectionDialog::baudRates() {
  static const std::vector<int> kRates{9600, 19200, 38400, 57600, 115200, 230400, 460800, 921600};
  return kRates;
}

QString ConnectionDialog::serialUrl(const QString& path, int baud) {
  return QStringLiteral("serial://%1?baud=%2").arg(path).arg(baud);
}

ConnectionDialog::ConnectionDialog(ConnectionDialogOptions options, QWidget* parent)
    : QDialog(parent), options_(std::move(options)) {
  setWindowTitle(tr("Connect to Robot"));
  setObjectName(QStringLiteral("connectionDialog"));

  auto* source = new QGroupBox(tr("Link"), this);
  port_radio_ = new QRadioButton(tr("Serial / Bluetooth port"), source);
  port_radio_->setObjectName(QStringLiteral("linkUsePort"));
  url_radio_ = new QRadioButton(tr("URL"), source);
  url_radio_->setObjectName(QStringLiteral("linkUseUrl"));
  source_group_ = new QButtonGroup(this);
  source_group_->addButton(port_radio_, kPortId);
  source_group_->addButton(url_radio_, kUrlId);

  port_combo_ = new QComboBox(source);
  port_combo_->setObjectName(QStringLiteral("linkPort"));
  port_combo_->setMinimumContentsLength(36);
  port_combo_->setSizeAdjustPolicy(QComboBox::AdjustToMinimumContentsLengthWithIcon);
  port_combo_->setToolTip(tr("Serial ports and bound Bluetooth (RFCOMM) devices of this computer"));
  refresh_button_ = new QToolButton(source);
  refresh_button_->setObjectName(QStringLiteral("linkRefreshPorts"));
  refresh_button_->setIcon(style()->standardIcon(QStyle::SP_BrowserReload));
  refresh_button_->setToolTip(tr("List the ports again"));
  refresh_button_->setVisible(static_cast<bool>(options_.rescan));
  baud_combo_ = new QComboBox(source);
  baud_combo_->setObjectName(QStringLiteral("linkBaud"));
  for (int baud : baudRates())
    baud_combo_->addItem(QString::number(baud), baud);
  baud_combo_->setToolTip(
      tr("UART speed of the robot; HC-05 Bluetooth modules default to 9600 or 38400"));
  url_edit_ = new QLineEdit(source);
  url_edit_->setObjectName(QStringLiteral("linkUrl"));
  url_edit_->setPlaceholderText(QStringLiteral("serial:///dev/ttyUSB0?baud=115200"));
  url_edit_->setToolTip(
      tr("serial:///dev/ttyUSB0?baud=115200 (also /dev/rfcomm0), "
         "tcp://host:5760, tcp://:5760?listen=1 (this computer only; "
         "tcp://0.0.0.0:5760?listen=1 for every interface), udp://:14550 (likewise "
         "udp://0.0.0.0:14550)"));
  url_edit_->setClearButtonEnabled(true);

  auto* grid = new QGridLayout(source);
  grid->addWidget(port_radio_, 0, 0, 1, 3);
  auto* port_row = new QHBoxLayout;
  port_row->addWidget(port_combo_, 1);
  port_row->addWidget(refresh_button_);
  grid->addLayout(port_row, 1, 1, 1, 2);
  grid->addWidget(new QLabel(tr("Baud"), source), 2, 1);
  grid->addWidget(baud_combo_, 2, 2, Qt::AlignLeft);
  grid->addWidget(url_radio_, 3, 0, 1, 3);
  grid->addWidget(url_edit_, 4, 1, 1, 2);
  grid->setColumnMinimumWidth(0, 16);
  grid->setColumnStretch(2, 1);

  protocol_combo_ = new QComboBox(this);
  protocol_combo_->setObjectName(QStringLiteral("linkProtocol"));
  protocol_combo_->addItems(options_.protocols.isEmpty() ? QStringList{QStringLiteral("MAVLink 2")}
                                                         : options_.protocols);
  protocol_combo_->setEnabled(protocol_combo_->count() > 1);
  auto* form = new QFormLayout;
  form->addRow(tr("Protocol"), protocol_combo_);

  preview_ = new QLabel(this);
  preview_->setObjectName(QStringLiteral("linkPreview"));
  preview_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  preview_->setStyleSheet(QStringLiteral("color: palette(mid);"));
  error_ = new QLabel(this);
  error_->setObjectName(QStringLiteral("linkError"));
  error_->setWordWrap(true);
  error_->setStyleSheet(QStringLiteral("color: #c62828;"));
  error_->hide();

  buttons_ = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel, this);
  buttons_->button(QDialogButtonBox::Ok)->setText(tr("Connect"));
  connect(buttons_, &QDialogButtonBox::accepted, this, &ConnectionDialog::accept);
  connect(buttons_, &QDialogButtonBox::rejected, this, &ConnectionDialog::reject);

  if (options_.signing_tools.usable())
    signing_box_ = new SigningKeyBox(options_.signing_tools, options_.signing, this);

  auto* layout = new QVBoxLayout(this);
  layout->addWidget(source);
  layout->addLayout(form);
  if (signing_box_ != nullptr)
    layout->addWidget(signing_box_);
  layout->addWidget(preview_);
  layout->addWidget(error_);
  layout->addWidget(buttons_);

  connect(source_group_, &QButtonGroup::idClicked, this, [this] {
    updateEnabled();
    updatePreview();
  });
  connect(refresh_button_, &QToolButton::clicked, this, &ConnectionDialog::rescanPorts);
  for (QComboBox* combo : {port_combo_, baud_combo_})
    connect(combo, &QComboBox::currentIndexChanged, this, &ConnectionDialog::updatePreview);
  connect(url_edit_, &QLineEdit::textChanged, this, &ConnectionDialog::updatePreview);

  setPortList(options_.ports);
  setBaud(kDefaultBaud);
  // The last URL: its port when listed, else the URL field.
  const QString initial = options_.initial_url.trimmed();
  const auto parts = serialParts(initial);
  if (parts && port_combo_->findData(parts->path) >= 0) {
    selectPort(parts->path);
    if (parts->baud > 0)
      setBaud(parts->baud);
    url_edit_->setText(initial);
    setUsePort(true);
  } else {
    url_edit_->setText(initial);
    setUsePort(initial.isEmpty() && !options_.ports.empty());
  }
}

void ConnectionDialog::setPortList(const std::vector<LinkPortEntry>& ports) {
  const QString selected = port_combo_->currentData().toString();
  port_combo_->clear();
  for (const LinkPortEntry& port : ports) {
    port_combo_->addItem(portLabel(port), port.path);
    port_combo_->setItemData(port_combo_->count() - 1, port.description, Qt::ToolTipRole);
  }
  if (ports.empty())
    port_combo_->setPlaceholderText(tr("no serial or Bluetooth ports found"));
  const int index = port_combo_->findData(selected);
  port_combo_->setCurrentIndex(index >= 0 ? index : (ports.empty() ? -1 : 0));
  port_radio_->setEnabled(!ports.empty());
  if (ports.empty())
    setUsePort(false);
  updateEnabled();
  updatePreview();
}

void ConnectionDialog::rescanPorts() {
  if (options_.rescan)
    setPortList(options_.rescan());
}

void ConnectionDialog::selectPort(const QString& path) {
  const int index = port_combo_->findData(path);
  if (index >= 0)
    port_combo_->setCurrentIndex(index);
}

void ConnectionDialog::setBaud(int baud) {
  int index = baud_combo_->findData(baud);
  if (index < 0 && baud > 0) {  // an unusual rate from a saved URL keeps its own entry
    baud_combo_->addItem(QString::number(baud), baud);
    index = baud_combo_->count() - 1;
  }
  if (index >= 0)
    baud_combo_->setCurrentIndex(index);
}

void ConnectionDialog::setUrlText(const QString& text) {
  url_edit_->setText(text);
}

void ConnectionDialog::setUsePort(bool use_port) {
  const bool port = use_port && port_combo_->count() > 0;
  (port ? port_radio_ : url_radio_)->setChecked(true);
  updateEnabled();
  updatePreview();
}

bool ConnectionDialog::usingPort() const {
  return port_radio_->isChecked();
}

QString ConnectionDialog::url() const {
  if (usingPort()) {
    const QString path = port_combo_->currentData().toString();
    return path.isEmpty() ? QString() : serialUrl(path, baud_combo_->currentData().toInt());
  }
  return url_edit_->text().trimmed();
}

QString ConnectionDialog::protocol() const {
  return protocol_combo_->currentText();
}

SigningChoice ConnectionDialog::signing() const {
  return signing_box_ != nullptr ? signing_box_->choice() : options_.signing;
}

QString ConnectionDialog::errorText() const {
  return error_->text();
}

void ConnectionDialog::updateEnabled() {
  const bool port = usingPort();
  port_combo_->setEnabled(port);
  refresh_button_->setEnabled(true);
  baud_combo_->setEnabled(port);
  url_edit_->setEnabled(!port);
}

void ConnectionDialog::updatePreview() {
  const QString text = url();
  preview_->setText(text.isEmpty() ? tr("Choose a port or enter a URL")
                                   : tr("Connects to %1").arg(text));
  error_->clear();
  error_->hide();
}

void ConnectionDialog::accept() {
  const QString text = url();
  QString problem;
  if (text.isEmpty())
    problem = usingPort() ? tr("No port selected.")
                          : tr("Enter a URL, e.g. %1").arg(url_edit_->placeholderText());
  else if (options_.validate)
    problem = options_.validate(text);
  if (!problem.isEmpty()) {
    error_->setText(problem);
    error_->show();
    return;
  }
  if (signing_box_ != nullptr && options_.save_signing)
    options_.save_signing(signing_box_->choice());
  QDialog::accept();
}

}  // namespace irgs::widgets
