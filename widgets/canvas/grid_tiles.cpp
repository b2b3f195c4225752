#include "widgets/canvas/grid_tiles.hpp"

#include <QPainter>
#include <algorithm>
#include <cstring>

#include "widgets/canvas/grid_image.hpp"

namespace irgs::widgets {
namespace {

std::int64_t tileKey(int tx, int ty) {
  return (static_cast<std::int64_t>(tx) << 32) | static_cast<std::uint32_t>(ty);
}

// Floor division for tile indices of negative cells.
int floorDiv(int a, int b) {
  return a >= 0 ? a / b : -((-a + b - 1) / b);
}

}  // namespace

OccupancyGrid::CellRect GridTiles::blit(const OccupancyGrid& grid, OccupancyGrid::CellRect cells) {
  if (cells.empty())
    return cells;
  const OccupancyGrid::CellRect observed = grid.observedCellRect();
  cells.col0 = std::max(cells.col0, observed.col0);
  cells.row0 = std::max(cells.row0, observed.row0);
  cells.col1 = std::min(cells.col1, observed.col1);
  cells.row1 = std::min(cells.row1, observed.row1);
  if (cells.empty())
    return cells;

  const int tx0 = floorDiv(cells.col0, kTileCells), tx1 = floorDiv(cells.col1, kTileCells);
  const int ty0 = floorDiv(cells.row0, kTileCells), ty1 = floorDiv(cells.row1, kTileCells);
  for (int ty = ty0; ty <= ty1; ++ty) {
    for (int tx = tx0; tx <= tx1; ++tx) {
      const int tile_col0 = tx * kTileCells, tile_row0 = ty * kTileCells;
      const OccupancyGrid::CellRect part{std::max(cells.col0, tile_col0),
                                         std::max(cells.row0, tile_row0),
                                         std::min(cells.col1, tile_col0 + kTileCells - 1),
                                         std::min(cells.row1, tile_row0 + kTileCells - 1)};
      const QImage piece = gridToImage(grid, part);
      if (piece.isNull())
        continue;
      Tile& tile = tiles_[tileKey(tx, ty)];
      if (tile.full.isNull()) {
        tile.full = QImage(kTileCells, kTileCells, QImage::Format_ARGB32_Premultiplied);
        tile.full.fill(Qt::transparent);
      }
      // Image row 0 of the tile is its top row (tile_row0 + kTileCells - 1).
      const int dst_x = part.col0 - tile_col0;
      const int dst_y = tile_row0 + kTileCells - 1 - part.row1;
      const auto bytes = static_cast<std::size_t>(piece.width()) * sizeof(QRgb);
      for (int y = 0; y < piece.height(); ++y) {
        std::memcpy(reinterpret_cast<QRgb*>(tile.full.scanLine(dst_y + y)) + dst_x,
                    piece.constScanLine(y), bytes);
      }
      tile.reduced_stale = true;
    }
  }
  return cells;
}

void GridTiles::paint(QPainter& p, const OccupancyGrid& grid, const MapView& view) {
  if (tiles_.empty())
    return;
  const double res = grid.resolution_m();
  const double cell_px = res * view.scale;
  const bool use_reduced = cell_px * kTileMipFactor < 2.0;
  p.save();
  p.setRenderHint(QPainter::Antialiasing, false);
  // Crisp cells when zoomed in, filtered when cells are smaller than a pixel.
  p.setRenderHint(QPainter::SmoothPixmapTransform, cell_px < 1.0);

  // Visible tile range.
  const Vec2 w0 = view.widgetToWorld(QPointF(0, view.size.height()));
  const Vec2 w1 = view.widgetToWorld(QPointF(view.size.width(), 0));
  const Cell c0 = grid.cellAt(w0), c1 = grid.cellAt(w1);
  const int tx0 = floorDiv(c0.col, kTileCells), tx1 = floorDiv(c1.col, kTileCells);
  const int ty0 = floorDiv(c0.row, kTileCells), ty1 = floorDiv(c1.row, kTileCells);
  const bool iterate_map = static_cast<long long>(tx1 - tx0 + 1) * (ty1 - ty0 + 1) >
                           static_cast<long long>(tiles_.size());

  auto draw = [&](std::int64_t key, Tile& tile) {
    const int tx = static_cast<int>(key >> 32);
    const int ty = static_cast<int>(static_cast<std::int32_t>(key & 0xffffffff));
    if (tx < tx0 || tx > tx1 || ty < ty0 || ty > ty1)
      return;
    const Vec2 corner = grid.cellCentre({tx * kTileCells, ty * kTileCells}) -
                        Vec2(res / 2.0, res / 2.0);  // lower-left of the tile
    const double span = kTileCells * res;
    const QRectF target(view.worldToWidget(Vec2(corner.x(), corner.y() + span)),
                        view.worldToWidget(Vec2(corner.x() + span, corner.y())));
    if (use_reduced) {
      if (tile.reduced_stale || tile.reduced.isNull()) {
        tile.reduced = tile.full.scaled(kTileCells / kTileMipFactor, kTileCells / kTileMipFactor,
                                        Qt::IgnoreAspectRatio, Qt::SmoothTransformation);
        tile.reduced_stale = false;
      }
      p.drawImage(target, tile.reduced);
    } else {
      p.drawImage(target, tile.full);
    }
  };
  if (iterate_map) {
    for (auto& [key, tile] : tiles_)
      draw(key, tile);
  } else {
    for (int ty = ty0; ty <= ty1; ++ty) {
      for (int tx = tx0; tx <= tx1; ++tx) {
        const auto it = tiles_.find(tileKey(tx, ty));
        if (it != tiles_.end())
          draw(it->first, it->second);
      }
    }
  }
  p.restore();
}

}  // namespace irgs::widgets
