#pragma once
// Finiteness checks of core geometry: the canvas skips what it cannot draw instead of failing.

#include <cmath>

#include "core/geometry/types.hpp"

namespace irgs::widgets {

inline bool finite(const irgs::Vec2& p) {
  return std::isfinite(p.x()) && std::isfinite(p.y());
}
inline bool finite(const irgs::Pose2& p) {
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.theta);
}
inline bool finite(const irgs::Box2& b) {
  return !b.empty() && finite(b.min) && finite(b.max);
}

}  // namespace irgs::widgets
