#include "widgets/canvas/robot_painter.hpp"

#include <QPainter>
#include <QPainterPath>
#include <algorithm>
#include <cmath>

#include "widgets/canvas/canvas_palette.hpp"
#include "widgets/canvas/finite_geometry.hpp"

namespace irgs::widgets {

using namespace palette;

void RobotPainter::setProfile(const RobotProfile& profile) {
  profile_ = profile;
  body_polygon_.clear();
  for (const Vec2& p : profile_.body_outline) {
    if (finite(p))
      body_polygon_ << QPointF(p.x(), p.y());
  }
  if (body_polygon_.size() < 3)
    body_polygon_.clear();  // drawn as a disc of kFallbackBodyRadius_m
}

double RobotPainter::bodyRadius() const {
  if (body_polygon_.isEmpty())
    return kFallbackBodyRadius_m;
  double r = 0.0;
  for (const QPointF& p : body_polygon_)
    r = std::max(r, std::hypot(p.x(), p.y()));
  return r > 0.0 ? r : kFallbackBodyRadius_m;
}

void RobotPainter::paintSonar(QPainter& p, const MapView& view, const Pose2& pose,
                              const std::vector<std::optional<SonarState>>& sonar, double now_s,
                              double stale_s) const {
  for (std::size_t i = 0; i < sonar.size() && i < profile_.sonars.size(); ++i) {
    if (!sonar[i] || now_s - sonar[i]->time_s > stale_s)
      continue;
    const SonarSpec& spec = profile_.sonars[i];
    const SonarReading& r = sonar[i]->reading;
    const double range =
        r.echo ? std::clamp(r.range_m, 0.0, std::max(spec.max_range_m, 0.0)) : spec.max_range_m;
    if (!std::isfinite(range) || !finite(spec.mount) || range * view.scale < 1.0)
      continue;
    const Pose2 mount = pose.compose(spec.mount);
    const QPointF apex = view.worldToWidget(mount.position());
    const double radius = range * view.scale;
    const double width_deg = std::clamp(radToDeg(spec.beam_width_rad), 0.5, 360.0);
    const double start_deg = radToDeg(mount.theta) - width_deg / 2.0;  // Qt: CCW on screen
    const QRectF box(apex - QPointF(radius, radius), QSizeF(2 * radius, 2 * radius));
    QPainterPath cone(apex);
    cone.arcTo(box, start_deg, width_deg);
    cone.closeSubpath();
    if (r.echo) {
      p.setPen(cosmeticPen(kEchoOutline, 1.0));
      p.setBrush(kEchoFill);
      p.drawPath(cone);
      QPainterPath arc;
      arc.arcMoveTo(box, start_deg);
      arc.arcTo(box, start_deg, width_deg);
      p.setPen(cosmeticPen(kEchoArc, 2.5));
      p.setBrush(Qt::NoBrush);
      p.drawPath(arc);
    } else {
      p.setPen(cosmeticPen(kNoEchoOutline, 1.0, Qt::DashLine));
      p.setBrush(kNoEchoFill);
      p.drawPath(cone);
    }
  }
}

void RobotPainter::paintRobot(QPainter& p, const MapView& view, const Pose2& pose,
                              std::uint32_t bumpers, bool ghost) const {
  const double radius = bodyRadius();
  const double c = std::cos(pose.theta), s = std::sin(pose.theta);
  p.save();
  if (radius * view.scale < kMinRobotRadius_px) {
    // Too small to show its shape: a fixed-size disc with a heading tick.
    const QPointF centre = view.worldToWidget(pose.position());
    const QPointF tip = centre + QPointF(c, -s) * (kMinRobotRadius_px + 5.0);
    if (ghost) {
      p.setPen(cosmeticPen(kTruthColour, 1.5, Qt::DashLine));
      p.setBrush(Qt::NoBrush);
    } else {
      p.setPen(cosmeticPen(kRobotOutline, 1.5));
      p.setBrush(kRobotFill);
    }
    p.drawEllipse(centre, kMinRobotRadius_px, kMinRobotRadius_px);
    p.drawLine(centre, tip);
    p.restore();
    return;
  }

  // Body frame -> world -> widget.
  p.setTransform(QTransform(c, s, -s, c, pose.x, pose.y) * view.worldTransform());
  if (ghost) {
    p.setPen(cosmeticPen(kTruthColour, 1.6, Qt::DashLine));
    p.setBrush(QColor(kTruthColour.red(), kTruthColour.green(), kTruthColour.blue(), 25));
  } else {
    p.setPen(cosmeticPen(kRobotOutline, 1.6));
    p.setBrush(kRobotFill);
  }
  if (body_polygon_.isEmpty())
    p.drawEllipse(QPointF(0, 0), radius, radius);
  else
    p.drawPolygon(body_polygon_);

  // Heading arrow (a chevron pointing along body +x).
  const double r = radius;
  const QPolygonF arrow{QPointF(0.72 * r, 0), QPointF(-0.3 * r, 0.42 * r), QPointF(-0.08 * r, 0),
                        QPointF(-0.3 * r, -0.42 * r)};
  if (ghost) {
    p.setBrush(Qt::NoBrush);
    p.drawPolygon(arrow);
  } else {
    p.setPen(cosmeticPen(QColor(255, 255, 255, 235), 1.0));
    p.setBrush(QColor(255, 255, 255, 235));
    p.drawPolygon(arrow);

    // Bumpers: a bar along the face at each bumper; red and thick when pressed.
    for (std::size_t i = 0; i < profile_.bumpers.size(); ++i) {
      const BumperSpec& b = profile_.bumpers[i];
      if (!finite(b.position) || !std::isfinite(b.normal_rad))
        continue;
      const bool pressed = i < 32 && (bumpers >> i) & 1u;
      const Vec2 tangent(-std::sin(b.normal_rad), std::cos(b.normal_rad));
      const double half = std::isfinite(b.half_width_m) ? std::max(b.half_width_m, 0.01) : 0.05;
      const Vec2 a = b.position - tangent * half, e = b.position + tangent * half;
      p.setPen(cosmeticPen(pressed ? kBumperHit : kBumperIdle, pressed ? 5.0 : 2.5));
      p.drawLine(QPointF(a.x(), a.y()), QPointF(e.x(), e.y()));
    }
  }
  p.restore();
}

}  // namespace irgs::widgets
