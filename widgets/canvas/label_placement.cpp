#include "widgets/canvas/label_placement.hpp"

#include <array>
#include <limits>

namespace irgs::widgets {
namespace {

double overlapArea(const QRectF& r, const std::vector<QRectF>& taken) {
  double area = 0.0;
  for (const QRectF& t : taken) {
    const QRectF common = r.intersected(t);
    if (!common.isEmpty())
      area += common.width() * common.height();
  }
  return area;
}

}  // namespace

QRectF placeLabel(const QRectF& box, const QPointF& at, const std::vector<QRectF>& taken,
                  double gap_px) {
  const double w = box.width(), h = box.height();
  const std::array<QPointF, 4> top_lefts{
      at + QPointF(gap_px, -gap_px - h),  // above right: the usual place
      at + QPointF(gap_px, gap_px),       // below right
      at + QPointF(-gap_px - w, -gap_px - h),
      at + QPointF(-gap_px - w, gap_px),
  };
  QRectF best;
  double best_overlap = std::numeric_limits<double>::infinity();
  for (const QPointF& top_left : top_lefts) {
    const QRectF candidate(top_left, QSizeF(w, h));
    const double overlap = overlapArea(candidate, taken);
    if (overlap == 0.0)
      return candidate;
    if (overlap < best_overlap) {
      best_overlap = overlap;
      best = candidate;
    }
  }
  return best;
}

}  // namespace irgs::widgets
