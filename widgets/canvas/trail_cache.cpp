#include "widgets/canvas/trail_cache.hpp"

#include <QPainter>
#include <QPolygonF>
#include <cmath>

#include "widgets/canvas/canvas_palette.hpp"

namespace irgs::widgets {

using namespace palette;

void TrailCache::update(const std::deque<Vec2>& trail, std::uint64_t pushed,
                        const QTransform& to_cache, const QPixmap& like) {
  constexpr std::uint64_t kRedrawAfterDropped = 1000;
  const std::uint64_t dropped = pushed - trail.size();
  const bool whole = !valid_ || upto_ < dropped + 1 || dropped - dropped_at_ >= kRedrawAfterDropped;
  if (!whole && upto_ == pushed)
    return;
  if (whole) {
    pixmap_ = QPixmap(like.size());
    pixmap_.setDevicePixelRatio(like.devicePixelRatio());
    pixmap_.fill(Qt::transparent);
    dropped_at_ = dropped;
  }
  const std::size_t first =
      whole ? 0 : static_cast<std::size_t>(upto_ - dropped - 1);  // last drawn point
  valid_ = true;
  upto_ = pushed;
  if (trail.size() < first + 2)
    return;

  QPainter p(&pixmap_);
  p.setRenderHint(QPainter::Antialiasing, true);
  QPen pen =
      cosmeticPen(QColor(kTrailColour.red(), kTrailColour.green(), kTrailColour.blue()), 2.0);
  p.setPen(pen);
  // Points closer than a pixel add nothing but cost; long polylines are stroked in pieces
  // (the stroker's cost grows faster than linearly with the vertex count).
  constexpr qsizetype kPiece = 256;
  QPolygonF line;
  line.reserve(kPiece + 1);
  QPointF last;
  for (std::size_t i = first; i < trail.size(); ++i) {
    const QPointF q = to_cache.map(QPointF(trail[i].x(), trail[i].y()));
    const bool is_last = i + 1 == trail.size();
    if (!line.isEmpty() && !is_last &&
        std::abs(q.x() - last.x()) + std::abs(q.y() - last.y()) < 1.5)
      continue;
    line << q;
    last = q;
    if (line.size() > kPiece) {
      p.drawPolyline(line);
      line.clear();
      line << q;
    }
  }
  if (line.size() >= 2)
    p.drawPolyline(line);
}

}  // namespace irgs::widgets
