#pragma once
// The view of the map canvas as a value: a uniform scale and the world point at the widget
// centre. World +x points right and +y points up on screen.

#include <QPointF>
#include <QSize>
#include <QTransform>

#include "core/geometry/types.hpp"

namespace irgs::widgets {

struct MapView {
  irgs::Vec2 centre = irgs::Vec2::Zero();  // world metres at the widget centre
  double scale = 50.0;                     // pixels per metre
  QSize size;                              // widget size, logical pixels

  QPointF worldToWidget(const irgs::Vec2& p) const {
    return {size.width() / 2.0 + (p.x() - centre.x()) * scale,
            size.height() / 2.0 - (p.y() - centre.y()) * scale};
  }
  irgs::Vec2 widgetToWorld(const QPointF& p) const {
    return {centre.x() + (p.x() - size.width() / 2.0) / scale,
            centre.y() - (p.y() - size.height() / 2.0) / scale};
  }
  // World metres -> widget pixels.
  QTransform worldTransform() const {
    return {scale,
            0.0,
            0.0,
            -scale,
            size.width() / 2.0 - centre.x() * scale,
            size.height() / 2.0 + centre.y() * scale};
  }
};

}  // namespace irgs::widgets
