#pragma once
// A log-odds occupancy grid that grows as the robot explores (1 cm cells by default), updated
// from sonar readings with a cone inverse sensor model.

#include <cstdint>
#include <optional>
#include <vector>

#include "core/geometry/types.hpp"
#include "core/world/raster_map.hpp"

namespace irgs {

struct Cell {
  int col = 0;
  int row = 0;
  friend bool operator==(const Cell&, const Cell&) = default;
};

// Inverse sensor model of one sonar reading (cone): cells inside the cone closer than the range
// become more likely free; cells on the arc at the range (thickness arc_thickness_m) become more
// likely occupied. Log-odds increments are added and clamped.
struct SonarInverseModel {
  double free_log_odds = -0.4;
  double occupied_log_odds = 0.85;
  double arc_thickness_m = 0.03;
  double clamp_min = -4.0;
  double clamp_max = 4.0;
  // Readings without an echo clear free space up to this range (0 disables).
  double no_echo_free_range_m = 1.5;
};

class OccupancyGrid {
 public:
  explicit OccupancyGrid(double resolution_m = 0.01);

  double resolution_m() const { return resolution_m_; }

  // Cell containing p. Cells exist everywhere: the grid grows when written.
  Cell cellAt(const Vec2& p) const;
  Vec2 cellCentre(const Cell& c) const;

  // Log-odds of a cell, 0 for never-observed cells.
  float logOdds(const Cell& c) const;
  double probability(const Cell& c) const;
  bool observed(const Cell& c) const;

  // Integrates one sonar cone: apex at origin, boresight heading_rad, full angle beam_width_rad.
  // With echo: free up to range - arc/2, occupied on the arc. Without echo: free up to
  // model.no_echo_free_range_m (capped at range).
  void integrateSonar(const Vec2& origin, double heading_rad, double beam_width_rad, double range_m,
                      bool echo, const SonarInverseModel& model);

  // Bounding box of all observed cells in world metres (empty box when nothing observed).
  Box2 observedBounds() const;
  // Area of observed cells (known free or occupied), m².
  double exploredArea_m2() const;

  // Cells touched since the last call, as a box in cell coordinates, for incremental redraw.
  struct CellRect {
    int col0 = 0, row0 = 0, col1 = -1, row1 = -1;  // inclusive; empty when col1 < col0
    bool empty() const { return col1 < col0 || row1 < row0; }
  };
  CellRect takeDirtyRect();

  // Exports the observed part as a raster with ROS-style values (-1, 0..100).
  RasterMap toRaster() const;

  // Number of cell updates performed since construction (for benchmarks and tests).
  std::uint64_t cellUpdates() const { return cell_updates_; }

 private:
  // Storage is described in occupancy_grid.cpp.
  double resolution_m_;
  std::uint64_t cell_updates_ = 0;
  struct Storage;
  std::shared_ptr<Storage> storage_;
};

}  // namespace irgs
