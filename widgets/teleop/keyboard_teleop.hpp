#pragma once
// Keyboard driving: install as an application event filter (qApp->installEventFilter(teleop)).
//
// Arrows and WASD held drive (forward+left = arc), releasing a key stops that axis, Space stops
// (emits stopPressed and clears held keys). Auto-repeat is swallowed. Keys are left alone while
// a text-entry widget has focus (QLineEdit, editable QTextEdit/QPlainTextEdit, QAbstractSpinBox,
// editable QComboBox), while a modal dialog or popup is open, and when Ctrl/Alt/Meta is held
// (so shortcuts keep working). Losing application focus releases every key (never keeps
// driving without a key held).

#include <QObject>
#include <set>

namespace irgs::widgets {

class KeyboardTeleop : public QObject {
  Q_OBJECT

 public:
  explicit KeyboardTeleop(QObject* parent = nullptr);

  // Non-finite or negative values are ignored. Re-emits the command if keys are held.
  void setSpeeds(double linear_mps, double angular_radps);
  void setEnabled(bool enabled);
  bool enabled() const { return enabled_; }
  double linearCommand() const { return linear_; }
  double angularCommand() const { return angular_; }

  bool eventFilter(QObject* watched, QEvent* event) override;

 signals:
  void commandChanged(double linear_mps, double angular_radps);
  void stopPressed();

 private:
  void releaseAll();
  void update();

  double linear_speed_ = 0.2;   // m/s
  double angular_speed_ = 0.8;  // rad/s
  bool enabled_ = true;
  std::set<int> held_keys_;  // Qt::Key codes of the driving keys currently held
  double linear_ = 0.0;
  double angular_ = 0.0;
};

}  // namespace irgs::widgets
