#pragma once
// The static layers of the map canvas cached in two pixmaps rendered for one scale, covering
// the viewport plus a margin: re-rendered only when the scale or device pixel ratio changes,
// the view leaves the cached area, or the content changed (invalidate()).

#include <QPixmap>
#include <QPoint>
#include <QSize>
#include <QTransform>

#include "core/geometry/types.hpp"
#include "widgets/canvas/map_layers_painter.hpp"
#include "widgets/canvas/map_view.hpp"

namespace irgs::widgets {

class StaticLayerCache {
 public:
  static constexpr int kMargin_px = 256;  // the cache extends this far beyond the viewport

  void invalidate() { valid_ = false; }

  // Re-renders the pixmaps with `painter` when they do not serve `view` at `dpr`; true when it
  // did (anything drawn in cache coordinates must then be redrawn).
  bool ensure(const MapView& view, double dpr, const MapLayersPainter& painter,
              const StaticLayerVisibility& layers);

  // Where the pixmaps' top-left corner falls in the widget, rounded to whole pixels.
  QPoint topLeftIn(const MapView& view) const;
  // World metres -> cache pixmap pixels.
  QTransform toCache() const;

  const QPixmap& under() const { return under_; }  // floor, metric grid, raster
  const QPixmap& over() const { return over_; }    // walls ... graph, transparent background

 private:
  QPixmap under_;
  QPixmap over_;
  double scale_ = 0.0;
  irgs::Vec2 origin_ = irgs::Vec2::Zero();  // world point at the pixmaps' top-left corner
  QSize size_;                              // logical pixels
  bool valid_ = false;
};

}  // namespace irgs::widgets
