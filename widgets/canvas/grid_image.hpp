#pragma once
// Adapters from core rasters to QImage, shared by the map canvas and anyone exporting pictures.

#include <QColor>
#include <QImage>

#include "core/mapping/occupancy_grid.hpp"
#include "core/world/raster_map.hpp"

namespace irgs::widgets {

// Colours of the occupancy grid picture (opaque; unknown cells are fully transparent).
inline const QColor kGridFreeColour{222, 234, 246};
inline const QColor kGridOccupiedColour{38, 43, 54};
// Cells with occupancy probability below kGridFreeBelow are drawn in the free colour, above
// kGridOccupiedAbove in the occupied colour, with a smooth ramp between.
inline constexpr double kGridFreeBelow = 0.25;
inline constexpr double kGridOccupiedAbove = 0.75;

// One pixel per cell of `cells` (inclusive rect), row 0 of the image = the largest row (largest
// y). Unknown (never observed) cells are transparent, free cells light, occupied dark, uncertain
// cells in between. Format ARGB32_Premultiplied. An empty rect gives a null image.
QImage gridToImage(const irgs::OccupancyGrid& grid, const irgs::OccupancyGrid::CellRect& cells);

// A ROS-style raster as an image, top row = largest y: unknown a translucent grey, free
// transparent, occupied dark (blended by the 0..100 value). Null image for an empty raster.
QImage rasterToImage(const irgs::RasterMap& raster);

}  // namespace irgs::widgets
