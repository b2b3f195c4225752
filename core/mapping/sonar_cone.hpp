#pragma once
// Geometry of one sonar cone of the inverse sensor model and its rasterisation into row spans
// of grid cells. Pure geometry: no grid storage here (occupancy_grid.cpp applies the spans).
//
// The membership criterion (SonarCone::classify) is the single definition used everywhere. The
// rasteriser finds, per row, the exact column interval of each condition of the criterion:
// every condition is monotone along a row even in floating point (rounding is monotone), so an
// analytic estimate of each boundary (ray/row intersection, circle/row intersection: one sqrt
// per row) is taken as is when it lies further from every cell centre than a bound on the
// rounding errors of the estimate and of the criterion (the usual case), and is otherwise
// corrected by evaluating the criterion on the one or two cells around it. The result is
// therefore bit-for-bit the set of cells for which classify() says so.

#include <cstdint>
#include <vector>

#include "core/geometry/types.hpp"
#include "core/mapping/occupancy_grid.hpp"

namespace irgs {

enum class ConeZone : std::uint8_t { kOutside, kFree, kOccupied };

// World coordinate of the centre of cell index i along one axis. Every user of cell centres in
// the mapping code goes through this so that they all round identically.
inline double cellCentreCoordinate(int index, double resolution_m) {
  return (static_cast<double>(index) + 0.5) * resolution_m;
}

struct SonarCone {
  Vec2 apex = Vec2::Zero();
  double heading_rad = 0.0;
  double half_angle_rad = 0.0;
  Vec2 right_edge = Vec2::UnitX();  // unit vector of the boundary ray at heading - half angle
  Vec2 left_edge = Vec2::UnitX();   // unit vector of the boundary ray at heading + half angle
  double free_radius_m = 0.0;       // free: |d| < free_radius_m
  bool has_arc = false;             // occupied: free_radius_m <= |d| <= arc_outer_radius_m
  double arc_outer_radius_m = 0.0;
  double free_radius2 = 0.0;  // squares, computed once so that every test compares the same values
  double arc_outer_radius2 = 0.0;

  // Radius beyond which no cell belongs to the cone.
  double outerRadius() const { return has_arc ? arc_outer_radius_m : free_radius_m; }
  // The membership criterion for a cell centre at apex + (dx, dy).
  ConeZone classify(double dx, double dy) const;
  // The same criterion written with atan2 and hypot, as a reference (integrateSonarNaive). It
  // agrees with classify() except for centres within rounding error of a boundary.
  ConeZone classifyWithAngles(double dx, double dy) const;
  // The criterion for cell (col, row) of a grid, with (dx, dy) computed the one canonical way.
  ConeZone classifyCell(int col, int row, double resolution_m) const;
  ConeZone classifyCellWithAngles(int col, int row, double resolution_m) const;
};

// Builds the cone of one reading; arguments as OccupancyGrid::integrateSonar (validated there).
SonarCone makeSonarCone(const Vec2& origin, double heading_rad, double beam_width_rad,
                        double range_m, bool echo, const SonarInverseModel& model);

// Cells that can belong to the cone: the bounding box of the sector, padded by one cell.
OccupancyGrid::CellRect coneCellBounds(const SonarCone& cone, double resolution_m);

// A run of cells [col0, col1] (inclusive) of one row, all in the same zone.
struct ConeSpan {
  int row = 0;
  int col0 = 0;
  int col1 = 0;
  ConeZone zone = ConeZone::kFree;
  friend bool operator==(const ConeSpan&, const ConeSpan&) = default;
};

// The cone's cells in one row: [col0, col1] (col0 <= col1) are in the cone, of which [free0,
// free1] are free and the rest occupied (the arc band: at most one run on each side of the free
// run); free1 < free0 when no cell of the row is free.
struct ConeRow {
  int row = 0;
  int col0 = 0;
  int col1 = 0;
  int free0 = 0;
  int free1 = -1;
  bool hasFree() const { return free0 <= free1; }
  friend bool operator==(const ConeRow&, const ConeRow&) = default;
};

// Replaces `rows` with the cone's non-empty rows, ascending. Exactly the cells classify() puts in
// the cone (bit for bit). Cost per row: O(1) floating-point work and nothing per cell: the
// analytic boundary estimates (ray/row and circle/row intersections, one square root per disc)
// of all rows at once, vectorised, each used directly when clear of cell centres by more than
// its error bound; rows where one is not are scanned by scanConeRowsExact's per-row path (see
// sonar_cone_scan.hpp). `simd` picks the vector width (the rows do not depend on it); throws
// std::invalid_argument when the CPU does not support it.
void scanConeRows(const SonarCone& cone, double resolution_m, std::vector<ConeRow>& rows,
                  GridSimd simd = bestGridSimd());
// The same rows, every one by the exact path: each boundary estimate confirmed with two
// evaluations of the criterion and walked from when rounding puts it elsewhere. The reference
// for scanConeRows' fast path in tests; slower.
void scanConeRowsExact(const SonarCone& cone, double resolution_m, std::vector<ConeRow>& rows);

// Replaces `spans` with the cone's cells as row spans: rows ascending, within a row columns
// ascending, spans disjoint, never kOutside. Cost: O(rows) boundary work + no per-cell work.
void rasteriseCone(const SonarCone& cone, double resolution_m, std::vector<ConeSpan>& spans);

}  // namespace irgs
