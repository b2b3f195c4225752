#pragma once
// The picture of the live occupancy grid, kept as square tiles of kTileCells x kTileCells cells
// (one pixel per cell, top row = largest y) created where the grid was observed, so growth
// never copies and an update re-renders only the cells that changed.

#include <QImage>
#include <cstddef>
#include <cstdint>
#include <unordered_map>

#include "core/mapping/occupancy_grid.hpp"
#include "widgets/canvas/map_view.hpp"

class QPainter;

namespace irgs::widgets {

class GridTiles {
 public:
  static constexpr int kTileCells = 256;
  static constexpr int kTileMipFactor = 4;  // the reduced tile used when cells are < 0.5 px

  void clear() { tiles_.clear(); }
  bool empty() const { return tiles_.empty(); }
  std::size_t size() const { return tiles_.size(); }

  // Re-renders `cells` of `grid` into the tiles, clipped first to the grid's observed cells (a
  // runaway rect must not make us allocate or loop over nothing). Returns the clipped rect,
  // empty when nothing was drawn.
  irgs::OccupancyGrid::CellRect blit(const irgs::OccupancyGrid& grid,
                                     irgs::OccupancyGrid::CellRect cells);

  // Draws the tiles visible in `view`; `grid` must be the grid the tiles were made from.
  // Builds reduced tiles lazily, hence not const.
  void paint(QPainter& p, const irgs::OccupancyGrid& grid, const MapView& view);

 private:
  struct Tile {
    QImage full;
    QImage reduced;  // full scaled down by kTileMipFactor, rebuilt lazily
    bool reduced_stale = true;
  };
  std::unordered_map<std::int64_t, Tile> tiles_;
};

}  // namespace irgs::widgets
