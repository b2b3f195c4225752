#include "widgets/canvas/navigation_overlay.hpp"

#include <QFont>
#include <QPainter>
#include <QPainterPath>
#include <QPen>
#include <QPolygonF>
#include <cmath>

namespace irgs::widgets {

namespace {

// An arrow from `from` to `to` (widget pixels) with a small head.
void arrow(QPainter& p, const QPointF& from, const QPointF& to, const QColor& colour) {
  const QPointF d = to - from;
  const double len = std::hypot(d.x(), d.y());
  if (len < 2.0)
    return;
  p.setPen(QPen(colour, 2.5, Qt::SolidLine, Qt::RoundCap));
  p.drawLine(from, to);
  const QPointF u = d / len, n(-u.y(), u.x());
  const double head = std::min(9.0, 0.4 * len);
  QPolygonF tip;
  tip << to << to - u * head + n * head * 0.5 << to - u * head - n * head * 0.5;
  p.setBrush(colour);
  p.setPen(Qt::NoPen);
  p.drawPolygon(tip);
}

}  // namespace

void paintNavigationOverlay(QPainter& p, const MapView& view, const NavigationOverlay& overlay) {
  p.save();
  p.setRenderHint(QPainter::Antialiasing, true);
  for (const auto& outline : overlay.moving_obstacles) {
    QPolygonF poly;
    for (const irgs::Vec2& v : outline)
      poly << view.worldToWidget(v);
    p.setPen(QPen(QColor(120, 40, 160), 1.5));
    p.setBrush(QColor(160, 80, 200, 150));
    p.drawPolygon(poly);
  }
  // The route: travelled legs thin and pale, the legs ahead thick red (Fig. 15's A* path).
  const QColor ahead(220, 30, 30), behind(240, 170, 60);
  for (std::size_t i = 1; i < overlay.route.size(); ++i) {
    const bool done = overlay.next_node >= 0 && static_cast<int>(i) < overlay.next_node;
    p.setPen(QPen(done ? behind : ahead, done ? 3.0 : 4.0, Qt::SolidLine, Qt::RoundCap));
    p.drawLine(view.worldToWidget(overlay.route[i - 1]), view.worldToWidget(overlay.route[i]));
  }
  QFont font = p.font();
  font.setPointSizeF(9.0);
  font.setBold(true);
  p.setFont(font);
  for (std::size_t i = 0; i < overlay.route.size(); ++i) {
    const QPointF c = view.worldToWidget(overlay.route[i]);
    const bool next = static_cast<int>(i) == overlay.next_node;
    p.setPen(QPen(next ? QColor(20, 160, 60) : ahead, next ? 3.0 : 1.5));
    p.setBrush(Qt::NoBrush);
    const double r = next ? 11.0 : 7.0;
    p.drawEllipse(c, r, r);  // the graph layer already labels the node ids
  }
  if (overlay.robot) {
    const irgs::Pose2& pose = *overlay.robot;
    const QPointF at = view.worldToWidget(pose.position());
    const auto tip = [&](const irgs::Vec2& body) {
      const irgs::Vec2 w = pose.toWorld(body * overlay.vector_scale_m);
      return view.worldToWidget(w);
    };
    arrow(p, at, tip(overlay.repulsive), QColor(230, 120, 0));  // V_Repulsive_Sum
    arrow(p, at, tip(overlay.target), QColor(30, 110, 230));    // V_Target
    arrow(p, at, tip(overlay.move), QColor(20, 160, 60));       // V_Move
    if (!overlay.state.isEmpty()) {
      const QRectF box(at + QPointF(14.0, 10.0), QSizeF(120.0, 18.0));
      p.setPen(Qt::NoPen);
      p.setBrush(QColor(255, 255, 255, 210));
      p.drawRoundedRect(box, 4.0, 4.0);
      p.setPen(Qt::black);
      p.drawText(box, Qt::AlignCenter, overlay.state);
    }
  }
  p.restore();
}

}  // namespace irgs::widgets
