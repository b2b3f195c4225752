#include "app/gui/automation.hpp"

#include <QPixmap>
#include <QTextStream>
#include <QTimer>
#include <QWidget>
#include <cmath>

#include "app/gui/session_controller.hpp"

namespace irgs::gui {

Automation::Automation(SessionController& session, QWidget& window, Plan plan, QObject* parent)
    : QObject(parent), session_(session), window_(window), plan_(std::move(plan)) {}

void Automation::start() {
  if (!plan_.screenshot_file.isEmpty())
    connect(&session_, &SessionController::ticked, this, &Automation::onTick);
  if (plan_.quit_after_s) {
    const auto ms = static_cast<int>(std::lround(std::min(*plan_.quit_after_s, 1e6) * 1000.0));
    QTimer::singleShot(ms, this, &Automation::onQuitGuard);
  }
}

void Automation::onTick() {
  if (done_ || screenshot_taken_ || session_.displayTime_s() + 1e-9 < plan_.screenshot_after_s)
    return;
  // Only once the window is on screen and laid out: grab() renders it into a pixmap.
  if (!window_.isVisible())
    return;
  screenshot_taken_ = true;
  done_ = true;
  if (plan_.before_grab)
    plan_.before_grab();
  const QPixmap pixmap = window_.grab();
  QTextStream err(stderr);
  if (pixmap.isNull() || !pixmap.save(plan_.screenshot_file, "PNG")) {
    err << "irgs: error: cannot write screenshot " << plan_.screenshot_file << '\n';
    emit finished(kExitScreenshotFailed);
    return;
  }
  err << "irgs: screenshot " << plan_.screenshot_file << " (" << pixmap.width() << 'x'
      << pixmap.height() << ") at t = " << session_.displayTime_s() << " s\n";
  emit finished(0);
}

void Automation::onQuitGuard() {
  if (done_)
    return;
  done_ = true;
  if (!plan_.screenshot_file.isEmpty() && !screenshot_taken_) {
    QTextStream(stderr) << "irgs: error: --quit-after reached at simulated t = "
                        << session_.displayTime_s() << " s, before the screenshot at "
                        << plan_.screenshot_after_s << " s\n";
    emit finished(kExitTimedOut);
    return;
  }
  emit finished(0);
}

}  // namespace irgs::gui
