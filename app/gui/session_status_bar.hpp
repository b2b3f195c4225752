#pragma once
// The status bar fields: cursor position, simulated time, speed, mode and explored area.

#include <QObject>

class QLabel;
class QStatusBar;

namespace irgs::gui {

class SessionController;

class SessionStatusBar : public QObject {
  Q_OBJECT

 public:
  // Adds permanent fields to `bar` (which owns them).
  SessionStatusBar(QStatusBar& bar, QObject* parent = nullptr);

  void setCursor(double x_m, double y_m);
  void clearCursor();
  // Time, speed, mode and explored area from the session (explored area is the costly one:
  // call this a few times per second, not per frame).
  void refresh(SessionController& session);
  // Only the simulated time (cheap: every tick).
  void refreshTime(const SessionController& session);

 private:
  QLabel* cursor_ = nullptr;
  QLabel* time_ = nullptr;
  QLabel* speed_ = nullptr;
  QLabel* mode_ = nullptr;
  QLabel* explored_ = nullptr;
};

}  // namespace irgs::gui
