#include "widgets/canvas/metric_overlays.hpp"

#include <QFontMetricsF>
#include <QPainter>
#include <algorithm>
#include <cmath>

#include "widgets/canvas/canvas_palette.hpp"

namespace irgs::widgets {

using namespace palette;

namespace {

// The largest 1-2-5 step not longer than `limit` (> 0); `leading` receives 1, 2 or 5.
double niceStepBelow(double limit, int* leading = nullptr) {
  const double decade = std::pow(10.0, std::floor(std::log10(limit)));
  int lead = 1;
  if (5.0 * decade <= limit)
    lead = 5;
  else if (2.0 * decade <= limit)
    lead = 2;
  if (leading)
    *leading = lead;
  return lead * decade;
}

// The smallest 1-2-5 step at least `limit` (> 0).
double niceStepAbove(double limit, int* leading) {
  const double decade = std::pow(10.0, std::floor(std::log10(limit)));
  for (int lead : {1, 2, 5}) {
    if (lead * decade >= limit * (1.0 - 1e-9)) {
      *leading = lead;
      return lead * decade;
    }
  }
  *leading = 1;
  return 10.0 * decade;
}

QString lengthLabel(double metres) {
  if (metres >= 1000.0)
    return QStringLiteral("%1 km").arg(metres / 1000.0);
  if (metres >= 1.0)
    return QStringLiteral("%1 m").arg(metres);
  if (metres >= 0.01)
    return QStringLiteral("%1 cm").arg(std::round(metres * 1000.0) / 10.0);
  return QStringLiteral("%1 mm").arg(std::round(metres * 10000.0) / 10.0);
}

}  // namespace

void paintMetricGrid(QPainter& p, const QTransform& world, const QRectF& world_rect, double scale,
                     const QSize& area) {
  int leading = 1;
  const double step = niceStepAbove(40.0 / scale, &leading);  // >= 40 px between lines
  const int major_every = leading == 5 ? 2 : 5;               // major lines at 5, 10 or 10 x 10^k
  p.save();
  p.setRenderHint(QPainter::Antialiasing, false);
  const double x0 = world_rect.left(), x1 = world_rect.right();
  const double y0 = world_rect.top(), y1 = world_rect.bottom();  // world y0 < y1
  const auto first_x = static_cast<long long>(std::floor(x0 / step));
  const auto last_x = static_cast<long long>(std::ceil(x1 / step));
  const auto first_y = static_cast<long long>(std::floor(y0 / step));
  const auto last_y = static_cast<long long>(std::ceil(y1 / step));
  const double top = 0.0, bottom = area.height();
  const double left = 0.0, right = area.width();
  for (int pass = 0; pass < 2; ++pass) {  // minor lines first, major on top
    const bool major_pass = pass == 1;
    p.setPen(QPen(major_pass ? kMajorGridColour : kMinorGridColour, 1.0));
    for (long long i = first_x; i <= last_x; ++i) {
      if ((i % major_every == 0) != major_pass)
        continue;
      const double x = std::round(world.map(QPointF(static_cast<double>(i) * step, 0)).x()) + 0.5;
      p.drawLine(QPointF(x, top), QPointF(x, bottom));
    }
    for (long long i = first_y; i <= last_y; ++i) {
      if ((i % major_every == 0) != major_pass)
        continue;
      const double y = std::round(world.map(QPointF(0, static_cast<double>(i) * step)).y()) + 0.5;
      p.drawLine(QPointF(left, y), QPointF(right, y));
    }
  }
  p.restore();
}

void paintScaleBar(QPainter& p, double scale, int height_px) {
  const double max_len_m = 140.0 / scale;
  const double len_m = niceStepBelow(max_len_m);
  const double len_px = len_m * scale;
  const QString label = lengthLabel(len_m);
  QFont font = p.font();
  font.setPointSizeF(8.5);
  p.setFont(font);
  const QFontMetricsF metrics(font);
  const double text_w = metrics.horizontalAdvance(label);
  const double left = 12.0, bottom = height_px - 12.0;
  const QRectF panel(left - 6.0, bottom - 12.0 - metrics.height() - 6.0,
                     std::max(len_px, text_w) + 12.0, 12.0 + metrics.height() + 10.0);
  p.setPen(Qt::NoPen);
  p.setBrush(QColor(255, 255, 255, 200));
  p.drawRoundedRect(panel, 4.0, 4.0);
  p.setPen(QPen(QColor(33, 33, 33), 2.0, Qt::SolidLine, Qt::FlatCap));
  const double y = bottom - 4.0;
  p.drawLine(QPointF(left, y), QPointF(left + len_px, y));
  p.drawLine(QPointF(left, y - 5.0), QPointF(left, y + 1.0));
  p.drawLine(QPointF(left + len_px, y - 5.0), QPointF(left + len_px, y + 1.0));
  p.drawText(QRectF(left, panel.top() + 3.0, std::max(len_px, text_w), metrics.height()),
             Qt::AlignHCenter | Qt::AlignVCenter, label);
}

}  // namespace irgs::widgets
