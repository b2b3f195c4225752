#pragma once
// MAVLink signing in the connection dialog: a switch, the key's fingerprint and the key's life
// cycle (a new random key, copy, export to a file for `irgs-robot --signing-key`, import). The
// key itself is never shown, only its fingerprint. The application supplies the key's rules
// (SigningKeyTools): widgets never see comms.

#include <QGroupBox>
#include <QString>
#include <functional>

class QCheckBox;
class QLabel;
class QPushButton;

namespace irgs::widgets {

struct SigningKeyTools {
  std::function<QString()> generate;  // a fresh random key, as key text
  // The canonical text of a key, or an empty string with the reason in *error.
  std::function<QString(const QString& text, QString* error)> parse;
  std::function<QString(const QString& key)> fingerprint;  // a short name to compare copies by
  bool usable() const { return generate && parse && fingerprint; }
};

struct SigningChoice {
  bool enabled = false;
  QString key;  // canonical key text; empty: no key yet
  friend bool operator==(const SigningChoice&, const SigningChoice&) = default;
};

class SigningKeyBox : public QGroupBox {
  Q_OBJECT

 public:
  // `tools` must be usable(); an initial key that does not parse is dropped.
  SigningKeyBox(SigningKeyTools tools, SigningChoice initial, QWidget* parent = nullptr);

  SigningChoice choice() const;
  QString fingerprintText() const;
  QString statusText() const;

  // What the buttons do, without the file dialogs (tests call these). Those returning a QString
  // return an error (also shown in the box), empty on success.
  void generateKey();
  QString setKeyText(const QString& text);
  void setSigningEnabled(bool enabled);  // refused without a key
  void copyKey() const;                  // to the clipboard, as key text
  // Writes the key text and a newline, readable by the owner only.
  QString exportKey(const QString& path);
  QString importKey(const QString& path);

 signals:
  void changed();

 private:
  void refresh();
  void showStatus(const QString& text, bool error);
  void exportWithDialog();
  void importWithDialog();

  SigningKeyTools tools_;
  QString key_;
  QCheckBox* enabled_ = nullptr;
  QLabel* fingerprint_ = nullptr;
  QLabel* status_ = nullptr;
  QPushButton* copy_ = nullptr;
  QPushButton* export_ = nullptr;
};

}  // namespace irgs::widgets
