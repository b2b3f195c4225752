#pragma once
// What is under the cursor: the element (and vertex) nearest a world point within a tolerance,
// and the elements inside a dragged box. World metres.

#include <cstddef>
#include <optional>
#include <vector>

#include "core/editing/map_edit.hpp"
#include "core/world/world_map.hpp"

namespace irgs::editing {

struct Hit {
  ElementRef ref;
  std::optional<std::size_t> vertex;  // a wall point / obstacle vertex under the cursor
  double distance_m = 0.0;
};

// Vertices (and light ends) beat the start pose, which beats features and graph nodes, which
// beat markers and lights (hit anywhere on them), which beat graph edges, which beat wall pieces
// and obstacle edges; an obstacle is also hit anywhere inside. Nothing within `tolerance_m` ->
// nullopt.
std::optional<Hit> hitTest(const WorldMap& map, const Vec2& p, double tolerance_m);

// Elements whose every point lies inside the box (the start pose, markers and nodes by their
// position, edges by their nodes).
std::vector<ElementRef> elementsInBox(const WorldMap& map, const Box2& box);

}  // namespace irgs::editing
