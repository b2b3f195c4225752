#pragma once
// The robot's trail as a cached picture. The trail only grows at its end, so new segments are
// stroked onto the pixmap; the whole trail is redrawn when the picture is invalidated (the
// static layer cache moved) or when enough old points were dropped from its start that the
// picture would show a visibly longer trail than the canvas keeps.

#include <QPixmap>
#include <QTransform>
#include <cstdint>
#include <deque>

#include "core/geometry/types.hpp"

namespace irgs::widgets {

class TrailCache {
 public:
  void invalidate() { valid_ = false; }

  // Brings the picture up to date. `trail` holds the last trail.size() of the `pushed` points
  // ever appended; `to_cache` maps world metres to pixels of `like`, whose size and device
  // pixel ratio the picture takes when it is redrawn whole.
  void update(const std::deque<irgs::Vec2>& trail, std::uint64_t pushed, const QTransform& to_cache,
              const QPixmap& like);

  // Opaque strokes on transparent: draw it with the trail colour's opacity, so overlapping
  // strokes share one uniform translucency.
  const QPixmap& pixmap() const { return pixmap_; }

 private:
  QPixmap pixmap_;
  bool valid_ = false;
  std::uint64_t upto_ = 0;        // trail points drawn (counted like `pushed`)
  std::uint64_t dropped_at_ = 0;  // points dropped when the trail was last drawn whole
};

}  // namespace irgs::widgets
