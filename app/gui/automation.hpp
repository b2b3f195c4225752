#pragma once
// Unattended runs for demos and tests: take a screenshot of the window once the session has
// shown a given amount of simulated time, and quit after a wall-clock guard time.

#include <QObject>
#include <QString>
#include <functional>
#include <optional>

class QWidget;

namespace irgs::gui {

class SessionController;

class Automation : public QObject {
  Q_OBJECT

 public:
  // Exit codes of an automated run.
  static constexpr int kExitScreenshotFailed = 1;
  static constexpr int kExitTimedOut = 3;

  struct Plan {
    QString screenshot_file;             // empty: no screenshot
    double screenshot_after_s = 0.0;     // simulated seconds shown before the grab
    std::optional<double> quit_after_s;  // wall-clock seconds, from start()
    std::function<void()> before_grab;   // brings throttled displays up to date
  };

  Automation(SessionController& session, QWidget& window, Plan plan, QObject* parent = nullptr);

  // Arms the quit guard and starts watching the session.
  void start();
  bool screenshotTaken() const { return screenshot_taken_; }

 signals:
  // The run is over: quit the application with this code.
  void finished(int exit_code);

 private:
  void onTick();
  void onQuitGuard();

  SessionController& session_;
  QWidget& window_;
  Plan plan_;
  bool screenshot_taken_ = false;
  bool done_ = false;
};

}  // namespace irgs::gui
