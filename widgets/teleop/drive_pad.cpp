#include "widgets/teleop/drive_pad.hpp"

#include <QEvent>
#include <QMouseEvent>
#include <QPainter>
#include <algorithm>
#include <cmath>

#include "core/robot/teleop_mapping.hpp"

namespace irgs::widgets {

DrivePad::DrivePad(QWidget* parent) : QWidget(parent) {
  setObjectName(QStringLiteral("drivePad"));
  setAccessibleName(tr("Drive pad"));
  setToolTip(tr("Drag the knob to drive: up is forward, right turns clockwise. Release to stop."));
  setSizePolicy(QSizePolicy::Preferred, QSizePolicy::Preferred);
}

void DrivePad::setMaxSpeeds(double linear_mps, double angular_radps) {
  if (std::isfinite(linear_mps) && linear_mps >= 0.0)
    max_linear_ = linear_mps;
  if (std::isfinite(angular_radps) && angular_radps >= 0.0)
    max_angular_ = angular_radps;
}

QPointF DrivePad::centre() const {
  return QPointF(width() / 2.0, height() / 2.0);
}

double DrivePad::radius() const {
  return std::max(10.0, std::min(width(), height()) / 2.0 - 14.0);
}

void DrivePad::moveKnob(const QPointF& widget_pos) {
  QPointF p = (widget_pos - centre()) / radius();
  const double length = std::hypot(p.x(), p.y());
  if (length > 1.0)
    p /= length;  // the knob stays on the pad's rim
  knob_ = p;
  const VelocityCommand c = mapStick(p.x(), p.y(), kDeadband, kExpo, max_linear_, max_angular_);
  update();
  if (c.linear_mps != last_linear_ || c.angular_radps != last_angular_) {
    last_linear_ = c.linear_mps;
    last_angular_ = c.angular_radps;
    emit commandChanged(c.linear_mps, c.angular_radps);
  }
}

void DrivePad::release() {
  const bool was = dragging_;
  dragging_ = false;
  knob_ = QPointF();
  last_linear_ = last_angular_ = 0.0;
  update();
  if (was)
    emit released();
}

void DrivePad::mousePressEvent(QMouseEvent* event) {
  if (event->button() != Qt::LeftButton || !isEnabled())
    return QWidget::mousePressEvent(event);
  dragging_ = true;
  moveKnob(event->position());
  event->accept();
}

void DrivePad::mouseMoveEvent(QMouseEvent* event) {
  if (!dragging_)
    return QWidget::mouseMoveEvent(event);
  moveKnob(event->position());
  event->accept();
}

void DrivePad::mouseReleaseEvent(QMouseEvent* event) {
  if (event->button() != Qt::LeftButton || !dragging_)
    return QWidget::mouseReleaseEvent(event);
  release();
  event->accept();
}

void DrivePad::hideEvent(QHideEvent* event) {
  release();  // a pad switched away (another tab) must not keep driving
  QWidget::hideEvent(event);
}

void DrivePad::changeEvent(QEvent* event) {
  if (event->type() == QEvent::EnabledChange && !isEnabled())
    release();
  QWidget::changeEvent(event);
}

void DrivePad::paintEvent(QPaintEvent*) {
  QPainter p(this);
  p.setRenderHint(QPainter::Antialiasing);
  const QPointF c = centre();
  const double r = radius();
  const QPalette& pal = palette();
  p.setPen(QPen(pal.mid().color(), 1.5));
  p.setBrush(pal.base());
  p.drawEllipse(c, r, r);
  // Cross hairs and the deadband.
  p.setPen(QPen(pal.mid().color(), 1.0, Qt::DashLine));
  p.drawLine(QPointF(c.x() - r, c.y()), QPointF(c.x() + r, c.y()));
  p.drawLine(QPointF(c.x(), c.y() - r), QPointF(c.x(), c.y() + r));
  p.setPen(Qt::NoPen);
  p.setBrush(pal.alternateBase());
  p.drawEllipse(c, kDeadband * r, kDeadband * r);
  // Forward marker.
  p.setPen(QPen(pal.text().color(), 1.0));
  p.drawText(QRectF(c.x() - 30, c.y() - r - 14, 60, 14), Qt::AlignCenter, tr("fwd"));
  // The knob.
  const QPointF k = c + knob_ * r;
  const QColor knob_colour = dragging_ ? pal.highlight().color() : pal.button().color();
  p.setPen(QPen(pal.dark().color(), 1.5));
  p.setBrush(isEnabled() ? knob_colour : pal.window().color());
  p.drawEllipse(k, 12.0, 12.0);
}

}  // namespace irgs::widgets
