#include "app/gui/session_status_bar.hpp"

#include <QFontDatabase>
#include <QLabel>
#include <QStatusBar>

#include "app/gui/event_format.hpp"
#include "app/gui/session_controller.hpp"

namespace irgs::gui {
namespace {

// A fixed-width field so the bar does not jitter as numbers change.
QLabel* addField(QStatusBar& bar, const QString& sample, const QString& tooltip) {
  auto* label = new QLabel(&bar);
  label->setFont(QFontDatabase::systemFont(QFontDatabase::FixedFont));
  label->setMinimumWidth(label->fontMetrics().horizontalAdvance(sample) + 12);
  label->setToolTip(tooltip);
  bar.addPermanentWidget(label);
  return label;
}

}  // namespace

SessionStatusBar::SessionStatusBar(QStatusBar& bar, QObject* parent) : QObject(parent) {
  cursor_ = addField(bar, QStringLiteral("x -000.00 m  y -000.00 m"),
                     tr("World position under the mouse"));
  time_ = addField(bar, QStringLiteral("t 00000.0 s"), tr("Simulated time"));
  speed_ = addField(bar, QStringLiteral("speed 1000×"), tr("Simulation speed factor"));
  mode_ = addField(bar, QStringLiteral("Simulator · running"), tr("Robot mode and state"));
  explored_ = addField(bar, QStringLiteral("explored 00000.00 m²"),
                       tr("Area of the occupancy grid observed by the sonars"));
  clearCursor();
}

void SessionStatusBar::setCursor(double x_m, double y_m) {
  cursor_->setText(QStringLiteral("x %1 m  y %2 m").arg(x_m, 7, 'f', 2).arg(y_m, 7, 'f', 2));
}

void SessionStatusBar::clearCursor() {
  cursor_->setText(QStringLiteral("x — m  y — m"));
}

void SessionStatusBar::refreshTime(const SessionController& session) {
  time_->setText(QStringLiteral("t %1 s").arg(session.displayTime_s(), 0, 'f', 1));
}

void SessionStatusBar::refresh(SessionController& session) {
  refreshTime(session);
  const bool simulated = session.simulationControl() != nullptr;
  speed_->setText(simulated
                      ? QStringLiteral("speed %1").arg(formatSpeedFactor(session.speedFactor()))
                      : QStringLiteral("speed —"));
  mode_->setText(simulated
                     ? (session.paused() ? tr("Simulator · paused") : tr("Simulator · running"))
                     : tr("Linked robot"));
  explored_->setText(
      QStringLiteral("explored %1 m²").arg(session.grid().exploredArea_m2(), 0, 'f', 2));
}

}  // namespace irgs::gui
