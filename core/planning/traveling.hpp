#pragma once
// The traveling algorithm's commands (003_… section 4.3, Figs. 4.8-4.10; digest 4.10): the host
// splits the final path at its turning points and sends the robot, one segment at a time, the
// turn (in quanta of 15 degrees by default) and the distance to the next turning point; the
// robot reports arrival at each turning point.

#include <vector>

#include "core/geometry/types.hpp"

namespace irgs {

struct TravelSegment {
  Vec2 from = Vec2::Zero();  // turning point where the segment starts, world metres
  Vec2 to = Vec2::Zero();    // next turning point
  double turn_rad =
      0.0;  // turn on the spot before driving, CCW positive, a multiple of the quantum
  double heading_rad = 0.0;  // heading after the turn (previous heading + turn, wrapped)
  double distance_m = 0.0;   // straight drive after the turn
  // Path direction minus the quantised heading, wrapped: what the quantum costs on this leg.
  double heading_error_rad = 0.0;
};

struct TravelPlan {
  std::vector<TravelSegment> segments;
  double total_distance_m = 0.0;
  int turns = 0;  // segments with a non-zero turn
};

// Splits points (a polyline, world metres) into segments starting from the robot heading
// initial_heading_rad. Repeated and collinear points are merged. quantum_rad = 0 keeps exact
// turns. Throws std::invalid_argument for non-finite points, heading or quantum, or a negative
// quantum. Fewer than two distinct points give an empty plan.
TravelPlan makeTravelPlan(const std::vector<Vec2>& points, double initial_heading_rad,
                          double quantum_rad = degToRad(15.0));

}  // namespace irgs
