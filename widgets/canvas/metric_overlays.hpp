#pragma once
// Metric references drawn over the map: grid lines at a 1-2-5 spacing and the scale bar.

#include <QRectF>
#include <QSize>
#include <QTransform>

class QPainter;

namespace irgs::widgets {

// Minor and major grid lines covering an area of `area` pixels that shows `world_rect` (world
// metres, y0 < y1) through `world` (world metres -> area pixels, `scale` pixels per metre).
// Lines are at least 40 px apart; major lines fall at 5, 10 or 10 x 10^k metres.
void paintMetricGrid(QPainter& p, const QTransform& world, const QRectF& world_rect, double scale,
                     const QSize& area);

// A scale bar of a 1-2-5 length at most 140 px long, in the bottom-left corner of a widget of
// height `height_px`, on a translucent panel.
void paintScaleBar(QPainter& p, double scale, int height_px);

}  // namespace irgs::widgets
