#pragma once
// What the ceiling camera can see: the ceiling plane with its markers, lights and other
// painted things (signs, tiles), in world metres. Built from a WorldMap, or directly by tests and
// the vision evaluation (which add distractors the map format does not describe).

#include <vector>

#include "core/camera/image.hpp"
#include "core/geometry/types.hpp"
#include "core/world/world_map.hpp"

namespace irgs {

// A coloured rectangle on the ceiling: centre, orientation of its length axis, side lengths.
struct CeilingRect {
  Vec2 centre = Vec2::Zero();
  double heading_rad = 0.0;
  double length_m = 0.2;
  double width_m = 0.2;

  bool contains(const Vec2& p) const;
  // Distance from p to the rectangle (0 inside).
  double distance(const Vec2& p) const;
  std::vector<Vec2> corners() const;  // counter-clockwise
};

// Linear reflectance in [0, 1] per channel (sRGB-ish values divided by 255).
struct Albedo {
  double r = 0.0;
  double g = 0.0;
  double b = 0.0;
};

struct PaintedRect {
  CeilingRect rect;
  Albedo albedo;
};

struct CeilingScene {
  double ceiling_height_m = 2.5;
  Albedo ceiling{0.62, 0.61, 0.58};
  double tile_size_m = 0.6;          // ceiling tile seams every tile_size_m (0: a plain ceiling)
  std::vector<CeilingRect> markers;  // fluorescent-red squares (002_…)
  std::vector<CeilingRect> lights;   // emitting tubes and panels
  std::vector<PaintedRect> decorations;  // anything else painted on the ceiling
};

// The fluorescent red of 002_…'s markers (it stays saturated under dim and bright light).
inline constexpr Albedo kMarkerRed{1.0, 0.16, 0.24};

// The map's ceiling: its markers and lights at its ceiling height (`ceiling_height_m` overrides
// the map's when > 0).
CeilingScene sceneFromMap(const WorldMap& map, double ceiling_height_m = 0.0);
// A light tube as a rectangle.
CeilingRect lightRect(const CeilingLight& light);

}  // namespace irgs
