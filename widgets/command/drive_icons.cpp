#include "widgets/command/drive_icons.hpp"

#include <QPainter>
#include <QPainterPath>
#include <QPixmap>
#include <cmath>
#include <numbers>

namespace irgs::widgets {
namespace {

constexpr double kCanvas = 24.0;  // icons are designed on a 24 x 24 grid
constexpr double kStroke = 2.6;

// Strokes `path` and puts an arrowhead at `tip` pointing along `direction`.
void drawArrow(QPainter& p, const QPainterPath& path, QPointF tip, QPointF direction) {
  const double len = std::hypot(direction.x(), direction.y());
  const QPointF d = direction / (len > 0.0 ? len : 1.0);
  const QPointF n(-d.y(), d.x());
  p.setBrush(Qt::NoBrush);
  p.drawPath(path);
  p.setBrush(p.pen().color());
  p.drawPolygon(QPolygonF{tip + d * 2.0, tip - d * 5.0 + n * 4.6, tip - d * 5.0 - n * 4.6});
}

void drawStraight(QPainter& p) {
  QPainterPath path(QPointF(12, 21));
  path.lineTo(12, 8);
  drawArrow(p, path, QPointF(12, 5), QPointF(0, -1));
}

void drawArc(QPainter& p) {
  // Forward and curving left: starts upwards, ends pointing up-left.
  QPainterPath path(QPointF(15, 21));
  path.quadTo(QPointF(15, 10), QPointF(8.5, 6.5));
  drawArrow(p, path, QPointF(6.5, 5.4), QPointF(-9, -5));
}

void drawTurn(QPainter& p) {
  // Turning on the spot counter-clockwise: three quarters of a circle.
  const QPointF centre(12, 13);
  const double r = 7.0;
  const double start = -40.0, sweep = 250.0;  // Qt degrees, counter-clockwise on screen
  QPainterPath path;
  const QRectF box(centre - QPointF(r, r), QSizeF(2 * r, 2 * r));
  path.arcMoveTo(box, start);
  path.arcTo(box, start, sweep);
  const double end = (start + sweep) * std::numbers::pi / 180.0;
  const QPointF tip = centre + QPointF(std::cos(end), -std::sin(end)) * r;
  drawArrow(p, path, tip, QPointF(-std::sin(end), -std::cos(end)));
}

QPixmap render(DriveIcon icon, const QColor& colour, int size_px) {
  QPixmap pixmap(size_px, size_px);
  pixmap.fill(Qt::transparent);
  QPainter p(&pixmap);
  p.setRenderHint(QPainter::Antialiasing, true);
  p.scale(size_px / kCanvas, size_px / kCanvas);
  // Mirrors turn one drawing into its left/right and forward/back variants.
  const bool mirror_x = icon == DriveIcon::kTurnRight || icon == DriveIcon::kArcForwardRight ||
                        icon == DriveIcon::kArcBackRight;
  const bool mirror_y = icon == DriveIcon::kBack || icon == DriveIcon::kArcBackLeft ||
                        icon == DriveIcon::kArcBackRight;
  p.translate(kCanvas / 2, kCanvas / 2);
  p.scale(mirror_x ? -1.0 : 1.0, mirror_y ? -1.0 : 1.0);
  p.translate(-kCanvas / 2, -kCanvas / 2);
  p.setPen(QPen(colour, kStroke, Qt::SolidLine, Qt::RoundCap, Qt::RoundJoin));
  switch (icon) {
    case DriveIcon::kForward:
    case DriveIcon::kBack:
      drawStraight(p);
      break;
    case DriveIcon::kTurnLeft:
    case DriveIcon::kTurnRight:
      drawTurn(p);
      break;
    default:
      drawArc(p);
      break;
  }
  return pixmap;
}

}  // namespace

QIcon makeDriveIcon(DriveIcon icon, const QColor& colour) {
  QIcon result;
  for (int size : {24, 32, 48, 64})
    result.addPixmap(render(icon, colour, size));
  QColor disabled = colour;
  disabled.setAlpha(90);
  for (int size : {24, 32, 48, 64})
    result.addPixmap(render(icon, disabled, size), QIcon::Disabled);
  return result;
}

}  // namespace irgs::widgets
