#include "widgets/teleop/keyboard_teleop.hpp"

#include <QAbstractSpinBox>
#include <QApplication>
#include <QComboBox>
#include <QKeyEvent>
#include <QLineEdit>
#include <QPlainTextEdit>
#include <QTextEdit>
#include <QWidget>
#include <cmath>

namespace irgs::widgets {
namespace {

enum class Axis { kNone, kForward, kBack, kLeft, kRight };

Axis axisOf(int key) {
  switch (key) {
    case Qt::Key_Up:
    case Qt::Key_W:
      return Axis::kForward;
    case Qt::Key_Down:
    case Qt::Key_S:
      return Axis::kBack;
    case Qt::Key_Left:
    case Qt::Key_A:
      return Axis::kLeft;
    case Qt::Key_Right:
    case Qt::Key_D:
      return Axis::kRight;
    default:
      return Axis::kNone;
  }
}

// True when keys typed now are meant for text, not for driving.
bool textEntryHasFocus() {
  const QWidget* w = QApplication::focusWidget();
  if (!w)
    return false;
  if (const auto* line = qobject_cast<const QLineEdit*>(w))
    return !line->isReadOnly();
  if (const auto* text = qobject_cast<const QTextEdit*>(w))
    return !text->isReadOnly();
  if (const auto* plain = qobject_cast<const QPlainTextEdit*>(w))
    return !plain->isReadOnly();
  if (qobject_cast<const QAbstractSpinBox*>(w))
    return true;
  if (const auto* combo = qobject_cast<const QComboBox*>(w))
    return combo->isEditable();
  return false;
}

bool dialogOrPopupOpen() {
  return QApplication::activeModalWidget() != nullptr ||
         QApplication::activePopupWidget() != nullptr;
}

}  // namespace

KeyboardTeleop::KeyboardTeleop(QObject* parent) : QObject(parent) {}

void KeyboardTeleop::setSpeeds(double linear_mps, double angular_radps) {
  if (std::isfinite(linear_mps) && linear_mps >= 0.0)
    linear_speed_ = linear_mps;
  if (std::isfinite(angular_radps) && angular_radps >= 0.0)
    angular_speed_ = angular_radps;
  update();
}

void KeyboardTeleop::setEnabled(bool enabled) {
  enabled_ = enabled;
  if (!enabled_)
    releaseAll();
}

void KeyboardTeleop::releaseAll() {
  held_keys_.clear();
  update();
}

void KeyboardTeleop::update() {
  bool forward = false, back = false, left = false, right = false;
  for (int key : held_keys_) {
    const Axis axis = axisOf(key);
    forward |= axis == Axis::kForward;
    back |= axis == Axis::kBack;
    left |= axis == Axis::kLeft;
    right |= axis == Axis::kRight;
  }
  // Up and W together still mean "forward once"; opposite keys cancel.
  const double linear = linear_speed_ * (static_cast<int>(forward) - static_cast<int>(back));
  const double angular = angular_speed_ * (static_cast<int>(left) - static_cast<int>(right));
  if (linear == linear_ && angular == angular_)
    return;
  linear_ = linear;
  angular_ = angular;
  emit commandChanged(linear_, angular_);
}

bool KeyboardTeleop::eventFilter(QObject* /*watched*/, QEvent* event) {
  switch (event->type()) {
    case QEvent::ApplicationDeactivate:
    case QEvent::WindowDeactivate:
      // Releases may never arrive once focus is elsewhere: never keep driving blind.
      if (!held_keys_.empty())
        releaseAll();
      return false;
    case QEvent::KeyPress:
    case QEvent::KeyRelease:
      break;
    default:
      return false;
  }
  // One key event may be offered to this filter several times (its window, then the focus
  // widget, then parents while ignored); every decision below depends only on global state, so
  // repeated offers are harmless, and a handled event is consumed at the first offer.
  auto* key_event = static_cast<QKeyEvent*>(event);
  const int key = key_event->key();
  const bool press = event->type() == QEvent::KeyPress;

  if (!press) {
    // A release of a held key always counts, wherever focus has gone meanwhile.
    if (held_keys_.count(key) == 0 || key_event->isAutoRepeat())
      return held_keys_.count(key) != 0;
    held_keys_.erase(key);
    update();
    return !textEntryHasFocus();
  }

  if (!enabled_ || textEntryHasFocus() || dialogOrPopupOpen())
    return false;
  if (key_event->modifiers() & (Qt::ControlModifier | Qt::AltModifier | Qt::MetaModifier))
    return false;

  if (key == Qt::Key_Space) {
    if (!key_event->isAutoRepeat()) {
      held_keys_.clear();
      update();
      emit stopPressed();
    }
    return true;
  }
  if (axisOf(key) == Axis::kNone)
    return false;
  if (key_event->isAutoRepeat())
    return true;  // the key is already held: nothing changes
  held_keys_.insert(key);
  update();
  return true;
}

}  // namespace irgs::widgets
