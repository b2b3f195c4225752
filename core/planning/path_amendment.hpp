#pragma once
// Path amendment (003_… section 4.2, Figs. 4.6 and 4.7; digest 4.9 and A003-3) and the
// turn-aware travel time. The robot stops to turn (in 15 degree quanta), so a path with fewer
// turning points is faster even when a little longer.
//
// Around each wave point the amendment takes P1, the last turning point before it, and P2, the
// first turning point after it (AmendOptions::search_depth also tries farther ones), and splits the
// rectangle with diagonal P1-P2 into two triangles. When one triangle is free of obstacles:
//   mode kStraightFirst (default, A003-3 reading (a)): go straight P1 -> P2 when its heading is
//     a multiple of the turn quantum (within heading_tolerance_rad), else reading (b);
//   mode kTriangleLegs (reading (b)): go along the free triangle's two legs (one turn at the
//     rectangle corner).
// A replacement is kept only when it lowers the turn-aware travel time. Then an optional
// line-of-sight pass replaces runs of vertices by one free segment whose heading is on the
// quantum. The result is collision-free on the grid it was amended on (free_space.hpp).

#include <cstddef>
#include <optional>
#include <vector>

#include "core/planning/planning_grid.hpp"

namespace irgs {

// t = length / speed + n_turns * turn_stop_s + sum |turn| / turn_rate   (digest 4.10 [A])
struct TravelTimeModel {
  double speed_mps = 0.2;
  double turn_stop_s = 1.0;  // stop, settle and restart per turning point
  double turn_rate_radps = degToRad(45.0);
};

// Angle below which a change of direction is not a turn (collinear up to rounding).
inline constexpr double kStraightTolerance_rad = 1e-6;

// The polyline without repeated points and without collinear interior vertices.
std::vector<Vec2> compressPath(const std::vector<Vec2>& points);
// Interior vertices where the direction changes.
int countTurns(const std::vector<Vec2>& points);
double pathLength(const std::vector<Vec2>& points);
// Throws std::invalid_argument for a non-finite or non-positive speed or turn rate, or a
// negative or non-finite stop time. initial_heading_rad adds the turn onto the first leg.
double travelTime(const std::vector<Vec2>& points, const TravelTimeModel& model,
                  std::optional<double> initial_heading_rad = std::nullopt);

enum class AmendMode { kStraightFirst, kTriangleLegs };

struct AmendOptions {
  AmendMode mode = AmendMode::kStraightFirst;
  double turn_quantum_rad = degToRad(15.0);
  double heading_tolerance_rad = degToRad(0.5);
  bool line_of_sight = true;  // the general simplification after the wave-point pass
  // Turning points tried on each side of a wave point: 1 = exactly 003's P1 and P2 (the
  // nearest ones); more also tries earlier P1 / later P2 (or the path's ends), keeping the
  // replacement with the lowest travel time.
  std::size_t search_depth = 3;
  TravelTimeModel time_model;
};

struct AmendResult {
  std::vector<Vec2> points;  // amended polyline (turning points only)
  int turns_before = 0;
  int turns_after = 0;
  double length_before_m = 0.0;
  double length_after_m = 0.0;
  double time_before_s = 0.0;
  double time_after_s = 0.0;
  int wave_points_amended = 0;
};

// True when heading_rad is within tolerance of a multiple of quantum_rad (quantum 0: any).
bool headingOnQuantum(double heading_rad, double quantum_rad, double tolerance_rad);

// path: the dense or compressed path (world points, e.g. PlanResult::points); wave_indices:
// indices into `path` of the wave points (entrances) it passes. Throws std::invalid_argument for
// an index out of range or invalid options (non-finite or negative quantum/tolerance, invalid
// time model, search_depth 0). A path that is not free on the grid is returned compressed,
// unamended.
AmendResult amendPath(const PlanningGrid& grid, const std::vector<Vec2>& path,
                      const std::vector<std::size_t>& wave_indices,
                      const AmendOptions& options = {});

}  // namespace irgs
