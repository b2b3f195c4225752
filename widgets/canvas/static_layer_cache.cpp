#include "widgets/canvas/static_layer_cache.hpp"

#include <QPainter>
#include <QRectF>

namespace irgs::widgets {

bool StaticLayerCache::ensure(const MapView& view, double dpr, const MapLayersPainter& painter,
                              const StaticLayerVisibility& layers) {
  const QPointF offset = view.worldToWidget(origin_);
  const bool covers = offset.x() <= 0.5 && offset.y() <= 0.5 &&
                      offset.x() + size_.width() >= view.size.width() - 0.5 &&
                      offset.y() + size_.height() >= view.size.height() - 0.5;
  if (valid_ && scale_ == view.scale && covers && under_.devicePixelRatio() == dpr)
    return false;

  scale_ = view.scale;
  size_ = view.size + QSize(2 * kMargin_px, 2 * kMargin_px);
  origin_ = view.widgetToWorld(QPointF(-kMargin_px, -kMargin_px));
  const QSize device_size = (QSizeF(size_) * dpr).toSize();
  const QTransform world = toCache();
  const QRectF world_rect(origin_.x(), origin_.y() - size_.height() / scale_,
                          size_.width() / scale_, size_.height() / scale_);

  under_ = QPixmap(device_size);
  under_.setDevicePixelRatio(dpr);
  {
    QPainter p(&under_);
    painter.paintUnder(p, world, world_rect, scale_, size_, layers);
  }
  over_ = QPixmap(device_size);
  over_.setDevicePixelRatio(dpr);
  over_.fill(Qt::transparent);
  {
    QPainter p(&over_);
    painter.paintOver(p, world, world_rect, scale_, layers);
  }
  valid_ = true;
  return true;
}

QPoint StaticLayerCache::topLeftIn(const MapView& view) const {
  const QPointF offset = view.worldToWidget(origin_);
  return {qRound(offset.x()), qRound(offset.y())};
}

QTransform StaticLayerCache::toCache() const {
  return {scale_, 0.0, 0.0, -scale_, -origin_.x() * scale_, origin_.y() * scale_};
}

}  // namespace irgs::widgets
