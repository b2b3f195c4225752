#pragma once
// Where a small label goes beside the point it names, so that labels of points that lie close
// together (a map-building index dropped where the robot passed before, at a loop's closure) do
// not print over each other.

#include <QPointF>
#include <QRectF>
#include <vector>

namespace irgs::widgets {

// `box` is the label's size (its position is ignored). Tries above-right of `at`, then
// below-right, above-left and below-left, `gap_px` off the point, and returns the first rectangle
// that overlaps none of `taken`; when all four do, the one that overlaps them least.
QRectF placeLabel(const QRectF& box, const QPointF& at, const std::vector<QRectF>& taken,
                  double gap_px = 6.0);

}  // namespace irgs::widgets
