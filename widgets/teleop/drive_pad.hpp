#pragma once
// On-screen drive pad: drag the knob with the mouse (or a touch screen) to drive. Up is
// forward, right turns clockwise; the distance from the centre sets the speed, shaped like the
// gamepad's stick (core/robot/teleop_mapping.hpp: deadband and expo). Releasing the knob, or
// the pad losing the mouse, snaps it back and stops the robot: the pad never keeps driving
// without a hand on it.

#include <QPointF>
#include <QWidget>

namespace irgs::widgets {

class DrivePad : public QWidget {
  Q_OBJECT

 public:
  explicit DrivePad(QWidget* parent = nullptr);

  // The speeds at full deflection (non-finite or negative values are ignored).
  void setMaxSpeeds(double linear_mps, double angular_radps);
  double maxLinear() const { return max_linear_; }
  double maxAngular() const { return max_angular_; }
  bool dragging() const { return dragging_; }
  // The knob in pad units: x right, y down, inside the unit circle.
  QPointF knob() const { return knob_; }

  QSize sizeHint() const override { return {160, 160}; }
  QSize minimumSizeHint() const override { return {90, 90}; }

 signals:
  // While dragging, whenever the command changes.
  void commandChanged(double linear_mps, double angular_radps);
  // The knob was released (or the drag was cancelled): stop.
  void released();

 protected:
  void paintEvent(QPaintEvent* event) override;
  void mousePressEvent(QMouseEvent* event) override;
  void mouseMoveEvent(QMouseEvent* event) override;
  void mouseReleaseEvent(QMouseEvent* event) override;
  void hideEvent(QHideEvent* event) override;
  void changeEvent(QEvent* event) override;

 private:
  void moveKnob(const QPointF& widget_pos);
  void release();
  QPointF centre() const;
  double radius() const;

  static constexpr double kDeadband = 0.08;
  static constexpr double kExpo = 0.3;
  double max_linear_ = 0.2;
  double max_angular_ = 0.8;
  bool dragging_ = false;
  QPointF knob_;
  double last_linear_ = 0.0;
  double last_angular_ = 0.0;
};

}  // namespace irgs::widgets
