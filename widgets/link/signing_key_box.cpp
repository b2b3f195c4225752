#include "widgets/link/signing_key_box.hpp"

#include <QCheckBox>
#include <QClipboard>
#include <QFile>
#include <QFileDialog>
#include <QGridLayout>
#include <QGuiApplication>
#include <QHBoxLayout>
#include <QLabel>
#include <QPushButton>

namespace irgs::widgets {
namespace {

// A key file is 65 bytes (64 hex digits and a newline); a larger file is not a key file.
constexpr qint64 kMaxKeyFileBytes = 256;

}  // namespace

SigningKeyBox::SigningKeyBox(SigningKeyTools tools, SigningChoice initial, QWidget* parent)
    : QGroupBox(tr("MAVLink signing"), parent), tools_(std::move(tools)) {
  setObjectName(QStringLiteral("linkSigningBox"));
  enabled_ =
      new QCheckBox(tr("Sign messages (a robot with the key refuses unsigned commands)"), this);
  enabled_->setObjectName(QStringLiteral("linkSigning"));
  enabled_->setToolTip(
      tr("MAVLink 2 signing: everything sent carries a signature made with the key, and only "
         "messages signed with it are accepted. ARCOS links are never signed."));
  fingerprint_ = new QLabel(this);
  fingerprint_->setObjectName(QStringLiteral("linkSigningFingerprint"));
  fingerprint_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  fingerprint_->setToolTip(
      tr("Fingerprint of the key (not the key): irgs-robot --signing-key prints the same one"));
  auto* generate = new QPushButton(tr("New key"), this);
  generate->setObjectName(QStringLiteral("linkSigningNewKey"));
  generate->setToolTip(tr("Make a new random key (kept in your settings when you connect)"));
  copy_ = new QPushButton(tr("Copy"), this);
  copy_->setObjectName(QStringLiteral("linkSigningCopy"));
  copy_->setToolTip(tr("Copy the key (64 hex digits) to the clipboard"));
  export_ = new QPushButton(tr("Export…"), this);
  export_->setObjectName(QStringLiteral("linkSigningExport"));
  export_->setToolTip(tr("Save the key to a file for irgs-robot --signing-key FILE"));
  auto* import = new QPushButton(tr("Import…"), this);
  import->setObjectName(QStringLiteral("linkSigningImport"));
  import->setToolTip(tr("Read a key file (64 hex digits)"));
  status_ = new QLabel(this);
  status_->setObjectName(QStringLiteral("linkSigningStatus"));
  status_->setWordWrap(true);
  status_->hide();

  auto* buttons = new QHBoxLayout;
  for (QPushButton* button : {generate, copy_, export_, import})
    buttons->addWidget(button);
  buttons->addStretch(1);
  auto* grid = new QGridLayout(this);
  grid->addWidget(enabled_, 0, 0, 1, 2);
  grid->addWidget(new QLabel(tr("Key"), this), 1, 0);
  grid->addWidget(fingerprint_, 1, 1);
  grid->addLayout(buttons, 2, 0, 1, 2);
  grid->addWidget(status_, 3, 0, 1, 2);
  grid->setColumnStretch(1, 1);

  connect(enabled_, &QCheckBox::toggled, this, [this] { emit changed(); });
  connect(generate, &QPushButton::clicked, this, &SigningKeyBox::generateKey);
  connect(copy_, &QPushButton::clicked, this, &SigningKeyBox::copyKey);
  connect(export_, &QPushButton::clicked, this, &SigningKeyBox::exportWithDialog);
  connect(import, &QPushButton::clicked, this, &SigningKeyBox::importWithDialog);

  QString ignored;
  key_ = initial.key.isEmpty() ? QString() : tools_.parse(initial.key, &ignored);
  enabled_->setChecked(initial.enabled && !key_.isEmpty());
  refresh();
}

SigningChoice SigningKeyBox::choice() const {
  return {enabled_->isChecked() && !key_.isEmpty(), key_};
}

QString SigningKeyBox::fingerprintText() const {
  return fingerprint_->text();
}

QString SigningKeyBox::statusText() const {
  return status_->isHidden() ? QString() : status_->text();
}

void SigningKeyBox::generateKey() {
  key_ = tools_.generate();
  refresh();
  showStatus(tr("New key: export it for the robot (irgs-robot --signing-key FILE)"), false);
  emit changed();
}

QString SigningKeyBox::setKeyText(const QString& text) {
  QString error;
  const QString key = tools_.parse(text, &error);
  if (key.isEmpty()) {
    showStatus(error, true);
    return error;
  }
  key_ = key;
  refresh();
  emit changed();
  return {};
}

void SigningKeyBox::setSigningEnabled(bool enabled) {
  enabled_->setChecked(enabled && !key_.isEmpty());
}

void SigningKeyBox::copyKey() const {
  if (!key_.isEmpty())
    QGuiApplication::clipboard()->setText(key_);
}

QString SigningKeyBox::exportKey(const QString& path) {
  if (key_.isEmpty())
    return tr("No key to export: make or import one first");
  QFile file(path);
  // Owner-only before the key goes in.
  if (!file.open(QIODevice::WriteOnly | QIODevice::Truncate) ||
      !file.setPermissions(QFileDevice::ReadOwner | QFileDevice::WriteOwner) ||
      file.write((key_ + QLatin1Char('\n')).toLatin1()) < 0 || !file.flush()) {
    const QString error = tr("Cannot write %1: %2").arg(path, file.errorString());
    showStatus(error, true);
    return error;
  }
  showStatus(tr("Key written to %1 (readable by you only)").arg(path), false);
  return {};
}

QString SigningKeyBox::importKey(const QString& path) {
  QFile file(path);
  if (!file.open(QIODevice::ReadOnly)) {
    const QString error = tr("Cannot read %1: %2").arg(path, file.errorString());
    showStatus(error, true);
    return error;
  }
  const QString text = QString::fromLatin1(file.read(kMaxKeyFileBytes));
  const QString error = setKeyText(text);
  if (!error.isEmpty()) {
    const QString message = tr("%1: %2").arg(path, error);
    showStatus(message, true);
    return message;
  }
  showStatus(tr("Key read from %1").arg(path), false);
  return {};
}

void SigningKeyBox::refresh() {
  const bool have_key = !key_.isEmpty();
  fingerprint_->setText(have_key ? tools_.fingerprint(key_) : tr("none yet"));
  enabled_->setEnabled(have_key);
  if (!have_key)
    enabled_->setChecked(false);
  copy_->setEnabled(have_key);
  export_->setEnabled(have_key);
}

void SigningKeyBox::showStatus(const QString& text, bool error) {
  status_->setText(text);
  status_->setStyleSheet(error ? QStringLiteral("color: #c62828;") : QString());
  status_->show();
}

void SigningKeyBox::exportWithDialog() {
  const QString path = QFileDialog::getSaveFileName(this, tr("Export signing key"),
                                                    QStringLiteral("irgs-signing.key"));
  if (!path.isEmpty())
    exportKey(path);
}

void SigningKeyBox::importWithDialog() {
  const QString path = QFileDialog::getOpenFileName(this, tr("Import signing key"));
  if (!path.isEmpty())
    importKey(path);
}

}  // namespace irgs::widgets
