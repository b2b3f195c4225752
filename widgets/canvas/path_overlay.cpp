#include "widgets/canvas/path_overlay.hpp"

#include <QFont>
#include <QFontMetricsF>
#include <QLineF>
#include <QPainter>
#include <QPainterPath>
#include <cmath>
#include <vector>

#include "widgets/canvas/canvas_palette.hpp"
#include "widgets/canvas/finite_geometry.hpp"
#include "widgets/canvas/label_placement.hpp"

namespace irgs::widgets {
namespace {

const QColor kRawPathColour(230, 81, 0, 200);
const QColor kAmendedColour(0, 121, 107);
const QColor kReachedColour(0, 77, 64);
const QColor kGoalColour(211, 47, 47);
const QColor kCoverageColour(67, 160, 71, 150);
const QColor kRegionOutline(25, 118, 210, 220);
const QColor kRegionFill(25, 118, 210, 28);
const QColor kIndexColour(173, 20, 87);
constexpr double kLabelSpacing_px = 16.0;

QPainterPath polylinePath(const MapView& view, const std::vector<Vec2>& points) {
  QPainterPath path;
  bool first = true;
  for (const Vec2& w : points) {
    if (!finite(w))
      continue;
    const QPointF q = view.worldToWidget(w);
    if (first)
      path.moveTo(q);
    else
      path.lineTo(q);
    first = false;
  }
  return path;
}

// Draws `text` beside `at`, clear of the rectangles in `taken` where it can be (placeLabel), and
// adds its own rectangle to them.
void drawLabel(QPainter& p, const QPointF& at, const QString& text, const QColor& colour,
               std::vector<QRectF>& taken) {
  QFont font = p.font();
  font.setPointSizeF(7.5);
  font.setBold(true);
  p.setFont(font);
  const QFontMetricsF metrics(font);
  const QRectF box = metrics.boundingRect(text).adjusted(-2.5, -1, 2.5, 1);
  const QRectF placed = placeLabel(box, at, taken);
  taken.push_back(placed);
  p.setPen(Qt::NoPen);
  p.setBrush(QColor(255, 255, 255, 215));
  p.drawRoundedRect(placed, 3, 3);
  p.setPen(colour);
  p.drawText(placed, Qt::AlignCenter, text);
}

void paintGoal(QPainter& p, const QPointF& g) {
  p.setBrush(Qt::NoBrush);
  p.setPen(palette::cosmeticPen(Qt::white, 4.0));
  p.drawEllipse(g, 7.0, 7.0);
  p.setPen(palette::cosmeticPen(kGoalColour, 2.0));
  p.drawEllipse(g, 7.0, 7.0);
  p.drawLine(g + QPointF(-11, 0), g + QPointF(-4, 0));
  p.drawLine(g + QPointF(4, 0), g + QPointF(11, 0));
  p.drawLine(g + QPointF(0, -11), g + QPointF(0, -4));
  p.drawLine(g + QPointF(0, 4), g + QPointF(0, 11));
}

}  // namespace

void paintPlanningOverlay(QPainter& p, const MapView& view, const PlanningOverlay& overlay) {
  std::vector<QRectF> labels;  // drawn so far: later labels keep clear of them
  p.save();
  p.setRenderHint(QPainter::Antialiasing, true);

  if (overlay.region && finite(*overlay.region) && !overlay.region->empty()) {
    const QRectF r =
        QRectF(view.worldToWidget(overlay.region->min), view.worldToWidget(overlay.region->max))
            .normalized();
    p.setBrush(kRegionFill);
    p.setPen(palette::cosmeticPen(kRegionOutline, 1.5, Qt::DashLine));
    p.drawRect(r);
  }

  if (overlay.coverage_path.size() >= 2) {
    p.setBrush(Qt::NoBrush);
    p.setPen(palette::cosmeticPen(kCoverageColour, 1.5));
    p.drawPath(polylinePath(view, overlay.coverage_path));
  }

  if (overlay.amended_path.size() >= 2) {
    p.setBrush(Qt::NoBrush);
    p.setPen(palette::cosmeticPen(QColor(255, 255, 255, 200), 5.0));
    p.drawPath(polylinePath(view, overlay.amended_path));
    p.setPen(palette::cosmeticPen(kAmendedColour, 2.6));
    p.drawPath(polylinePath(view, overlay.amended_path));
    // Turning points (interior vertices), numbered in driving order; reached ones filled. A
    // label closer than kLabelSpacing_px to the previous one is left out (clustered points).
    std::optional<QPointF> last_label;
    for (std::size_t i = 1; i + 1 < overlay.amended_path.size(); ++i) {
      const Vec2& w = overlay.amended_path[i];
      if (!finite(w))
        continue;
      const QPointF q = view.worldToWidget(w);
      const bool reached = i <= overlay.reached;
      p.setPen(palette::cosmeticPen(reached ? kReachedColour : kAmendedColour, 1.5));
      p.setBrush(reached ? kReachedColour : QColor(Qt::white));
      p.drawEllipse(q, 4.5, 4.5);
      if (!last_label || QLineF(*last_label, q).length() >= kLabelSpacing_px) {
        drawLabel(p, q, QString::number(i), kAmendedColour, labels);
        last_label = q;
      }
    }
  }

  // The raw A* path on top of the amended one (dashed), so both show where they coincide.
  if (overlay.raw_path.size() >= 2) {
    p.setBrush(Qt::NoBrush);
    p.setPen(palette::cosmeticPen(kRawPathColour, 1.6, Qt::DashLine));
    p.drawPath(polylinePath(view, overlay.raw_path));
    p.setPen(Qt::NoPen);
    p.setBrush(kRawPathColour);
    for (std::size_t i = 1; i + 1 < overlay.raw_path.size(); ++i) {
      if (finite(overlay.raw_path[i]))
        p.drawEllipse(view.worldToWidget(overlay.raw_path[i]), 2.2, 2.2);
    }
  }

  for (std::size_t i = 0; i < overlay.indices.size(); ++i) {
    const Vec2& w = overlay.indices[i];
    if (!finite(w))
      continue;
    const QPointF q = view.worldToWidget(w);
    QPolygonF diamond;
    diamond << q + QPointF(0, -5) << q + QPointF(5, 0) << q + QPointF(0, 5) << q + QPointF(-5, 0);
    p.setPen(palette::cosmeticPen(Qt::white, 1.0));
    p.setBrush(kIndexColour);
    p.drawPolygon(diamond);
    drawLabel(p, q, QString::number(i + 1), kIndexColour, labels);
  }

  if (overlay.goal && finite(*overlay.goal))
    paintGoal(p, view.worldToWidget(*overlay.goal));
  p.restore();
}

void paintRegionRubberBand(QPainter& p, const MapView& view, const Vec2& a, const Vec2& b) {
  if (!finite(a) || !finite(b))
    return;
  p.save();
  p.setRenderHint(QPainter::Antialiasing, true);
  const QRectF r = QRectF(view.worldToWidget(a), view.worldToWidget(b)).normalized();
  p.setBrush(kRegionFill);
  p.setPen(palette::cosmeticPen(kRegionOutline, 1.5, Qt::DashLine));
  p.drawRect(r);
  const QString size = QStringLiteral("%1 × %2 m")
                           .arg(std::abs(b.x() - a.x()), 0, 'f', 2)
                           .arg(std::abs(b.y() - a.y()), 0, 'f', 2);
  std::vector<QRectF> labels;
  drawLabel(p, r.topRight(), size, kRegionOutline, labels);
  p.restore();
}

}  // namespace irgs::widgets
