#pragma once
// The static layers of the map canvas, painted from a copy of the world map whose geometry is
// prepared once per map: floor, raster and origin axes under the live grid; ceiling, obstacles,
// walls, features and the topological graph over it.

#include <QColor>
#include <QImage>
#include <QLineF>
#include <QPainterPath>
#include <QPolygonF>
#include <QRectF>
#include <QSize>
#include <QTransform>
#include <string>
#include <vector>

#include "core/world/world_map.hpp"

class QPainter;

namespace irgs::widgets {

// Which static layers are drawn.
struct StaticLayerVisibility {
  bool raster = true;
  bool walls = true;  // walls and obstacles
  bool features = true;
  bool ceiling = true;  // ceiling lights and markers
  bool graph = true;
};

class MapLayersPainter {
 public:
  // Copies the map and prepares its geometry; non-finite points are skipped.
  void setMap(const irgs::WorldMap& map);
  const irgs::WorldMap& map() const { return map_; }

  // Both paint onto an area of `area` pixels that shows `world_rect` (world metres, y0 < y1)
  // through `world` (world metres -> area pixels, `scale` pixels per metre).
  // Floor (grey outside the map bounds), floor-plan image, metric grid, raster, world origin
  // axes; fills the area.
  void paintUnder(QPainter& p, const QTransform& world, const QRectF& world_rect, double scale,
                  const QSize& area, const StaticLayerVisibility& layers) const;
  // Ceiling, obstacles, walls, features, graph on a transparent area.
  void paintOver(QPainter& p, const QTransform& world, const QRectF& world_rect, double scale,
                 const StaticLayerVisibility& layers) const;

 private:
  irgs::WorldMap map_;
  std::vector<QLineF> wall_segments_;  // world metres
  std::vector<QPolygonF> obstacle_polygons_;
  QPainterPath light_path_;
  std::vector<QPolygonF> marker_polygons_;
  std::vector<QColor> marker_colours_;  // each marker's own colour (the map's)
  QImage raster_image_;                 // one pixel per raster cell, top row = largest y
  QImage floor_plan_image_;             // the floor-plan image, decoded once per file
  std::string floor_plan_path_;         // the file floor_plan_image_ was read from
};

}  // namespace irgs::widgets
