#include "widgets/canvas/map_layers_painter.hpp"

#include <QPainter>
#include <algorithm>
#include <cmath>
#include <string>
#include <unordered_map>

#include "widgets/canvas/canvas_palette.hpp"
#include "widgets/canvas/finite_geometry.hpp"
#include "widgets/canvas/grid_image.hpp"
#include "widgets/canvas/metric_overlays.hpp"

namespace irgs::widgets {

using namespace palette;

namespace {

// Liang-Barsky: clips `line` to `rect` (y up or down does not matter); false when outside.
bool clipToRect(QLineF& line, const QRectF& rect) {
  const double x0 = line.x1(), y0 = line.y1();
  const double dx = line.x2() - x0, dy = line.y2() - y0;
  double t0 = 0.0, t1 = 1.0;
  const double p[4] = {-dx, dx, -dy, dy};
  const double q[4] = {x0 - rect.left(), rect.right() - x0, y0 - rect.top(), rect.bottom() - y0};
  for (int i = 0; i < 4; ++i) {
    if (p[i] == 0.0) {
      if (q[i] < 0.0)
        return false;
      continue;
    }
    const double t = q[i] / p[i];
    if (p[i] < 0.0)
      t0 = std::max(t0, t);
    else
      t1 = std::min(t1, t);
    if (t0 > t1)
      return false;
  }
  line = QLineF(x0 + t0 * dx, y0 + t0 * dy, x0 + t1 * dx, y0 + t1 * dy);
  return true;
}

}  // namespace

void MapLayersPainter::setMap(const WorldMap& map) {
  map_ = map;
  // Walls are kept as separate segments (drawn with round caps, which look like round joins)
  // and obstacles as separate polygons: stroking one huge path with thousands of crossing
  // sub-paths is orders of magnitude slower in Qt's rasteriser, and segments can be clipped.
  wall_segments_.clear();
  for (const Wall& wall : map_.walls) {
    std::vector<QPointF> points;
    for (const Vec2& p : wall.points) {
      if (finite(p))
        points.emplace_back(p.x(), p.y());
    }
    for (std::size_t i = 0; i + 1 < points.size(); ++i)
      wall_segments_.emplace_back(points[i], points[i + 1]);
    if (wall.closed && points.size() > 2)
      wall_segments_.emplace_back(points.back(), points.front());
    if (points.size() == 1)
      wall_segments_.emplace_back(points.front(), points.front());
  }

  obstacle_polygons_.clear();
  for (const Obstacle& obstacle : map_.obstacles) {
    QPolygonF polygon;
    for (const Vec2& p : obstacle.polygon) {
      if (finite(p))
        polygon << QPointF(p.x(), p.y());
    }
    if (polygon.size() >= 3)
      obstacle_polygons_.push_back(std::move(polygon));
  }

  light_path_ = QPainterPath();
  for (const CeilingLight& light : map_.lights) {
    if (!finite(light.tube.a) || !finite(light.tube.b))
      continue;
    const double half = std::isfinite(light.width_m) ? std::max(light.width_m, 0.01) / 2.0 : 0.05;
    const Vec2 d = light.tube.b - light.tube.a;
    const Vec2 n = d.norm() > 1e-9 ? Vec2(-d.y(), d.x()).normalized() * half : Vec2(0.0, half);
    const Vec2 along = d.norm() > 1e-9 ? Vec2(d.normalized() * half) : Vec2(half, 0.0);
    // A tube is a rounded rectangle around its axis; drawn as a polygon with capped ends.
    QPolygonF tube;
    for (const Vec2& q : {Vec2(light.tube.a - along + n), Vec2(light.tube.b + along + n),
                          Vec2(light.tube.b + along - n), Vec2(light.tube.a - along - n)})
      tube << QPointF(q.x(), q.y());
    light_path_.addPolygon(tube);
    light_path_.closeSubpath();
  }

  marker_polygons_.clear();
  marker_colours_.clear();
  for (const CeilingMarker& marker : map_.markers) {
    if (!finite(marker.position) || !std::isfinite(marker.heading_rad))
      continue;
    const double half =
        std::isfinite(marker.size_m) ? std::clamp(marker.size_m, 0.02, 5.0) / 2 : 0.1;
    const Pose2 pose{marker.position.x(), marker.position.y(), marker.heading_rad};
    QPolygonF square;
    for (const Vec2& corner :
         {Vec2(half, half), Vec2(-half, half), Vec2(-half, -half), Vec2(half, -half)}) {
      const Vec2 w = pose.toWorld(corner);
      square << QPointF(w.x(), w.y());
    }
    marker_polygons_.push_back(square);
    marker_colours_.emplace_back(marker.colour.r, marker.colour.g, marker.colour.b);
  }

  raster_image_ = map_.raster ? rasterToImage(map_.raster->raster) : QImage();
  // The floor plan's pixels do not change with its calibration: decode only a new file.
  const std::string plan_path = map_.floor_plan ? map_.floor_plan->resolved_path : std::string();
  if (plan_path != floor_plan_path_) {
    floor_plan_path_ = plan_path;
    floor_plan_image_ = plan_path.empty() ? QImage() : QImage(QString::fromStdString(plan_path));
  }
}

void MapLayersPainter::paintUnder(QPainter& p, const QTransform& world, const QRectF& world_rect,
                                  double scale, const QSize& area,
                                  const StaticLayerVisibility& layers) const {
  const QRectF all(QPointF(0, 0), QSizeF(area));
  const Box2 map_box = map_.bounds();
  if (finite(map_box)) {
    p.fillRect(all, kOutsideColour);
    const QRectF floor =
        world.mapRect(QRectF(map_box.min.x(), map_box.min.y(), map_box.max.x() - map_box.min.x(),
                             map_box.max.y() - map_box.min.y()));
    // A soft margin around the mapped area so walls on the boundary do not touch the grey.
    p.fillRect(floor.adjusted(-12, -12, 12, 12), kFloorColour);
  } else {
    p.fillRect(all, kFloorColour);
  }

  if (layers.raster && !floor_plan_image_.isNull() && map_.floor_plan) {
    // Pixel (u, v) -> origin + R(rotation) * s * (u, -v) (core/editing/floor_plan.hpp).
    const FloorPlan& f = *map_.floor_plan;
    const double c = std::cos(f.rotation_rad) * f.metres_per_pixel;
    const double s = std::sin(f.rotation_rad) * f.metres_per_pixel;
    const QTransform image_to_world(c, s, s, -c, f.origin.x(), f.origin.y());
    p.save();
    p.setTransform(image_to_world * world);
    p.setOpacity(f.opacity);
    p.setRenderHint(QPainter::SmoothPixmapTransform, true);
    p.drawImage(QPointF(0, 0), floor_plan_image_);
    p.restore();
  }

  paintMetricGrid(p, world, world_rect, scale, area);

  if (layers.raster && !raster_image_.isNull() && map_.raster) {
    const RasterMap& r = map_.raster->raster;
    // Image pixel (u, v) -> world (ox + u res, oy + (H - v) res); the origin yaw is ignored
    // like ROS does (see raster_map.hpp).
    const QTransform image_to_world(r.resolution_m, 0.0, 0.0, -r.resolution_m, r.origin.x,
                                    r.origin.y + r.height * r.resolution_m);
    p.save();
    p.setTransform(image_to_world * world);
    p.setRenderHint(QPainter::SmoothPixmapTransform, r.resolution_m * scale < 2.0);
    p.drawImage(QPointF(0, 0), raster_image_);
    p.restore();
  }

  // World origin axes: x red, y green, 30 px.
  p.setRenderHint(QPainter::Antialiasing, true);
  const QPointF o = world.map(QPointF(0, 0));
  p.setPen(cosmeticPen(QColor(211, 47, 47, 170), 2.0));
  p.drawLine(o, o + QPointF(30, 0));
  p.setPen(cosmeticPen(QColor(56, 142, 60, 170), 2.0));
  p.drawLine(o, o + QPointF(0, -30));
}

void MapLayersPainter::paintOver(QPainter& p, const QTransform& world, const QRectF& world_rect,
                                 double scale, const StaticLayerVisibility& layers) const {
  p.setRenderHint(QPainter::Antialiasing, true);

  if (layers.ceiling) {
    p.save();
    p.setTransform(world);
    p.setPen(cosmeticPen(kLightOutline, 1.0));
    p.setBrush(kLightFill);
    p.drawPath(light_path_);
    for (std::size_t i = 0; i < marker_polygons_.size(); ++i) {
      // The default red keeps the palette's translucent look; other colours keep their hue.
      QColor fill = marker_colours_[i], outline = marker_colours_[i];
      fill.setAlpha(kMarkerFill.alpha());
      outline.setAlpha(kMarkerOutline.alpha());
      p.setPen(cosmeticPen(outline, 1.0));
      p.setBrush(fill);
      p.drawPolygon(marker_polygons_[i]);
    }
    p.restore();
  }

  if (layers.walls) {
    p.save();
    p.setTransform(world);
    p.setPen(cosmeticPen(kObstacleOutline, 1.2));
    p.setBrush(kObstacleFill);
    for (const QPolygonF& polygon : obstacle_polygons_)
      p.drawPolygon(polygon);
    // Walls are drawn about 5 cm thick, but never thinner than 2 px nor thicker than 8 px.
    const double wall_px = std::clamp(0.05 * scale, 2.0, 8.0);
    p.setPen(cosmeticPen(kWallColour, wall_px));
    // Segments are clipped to the cached area (plus the pen) before stroking: a long wall
    // crossing the view at a high zoom would otherwise be stroked over its whole length.
    const double pad = wall_px / scale;
    const QRectF clip = world_rect.adjusted(-pad, -pad, pad, pad);
    p.setBrush(Qt::NoBrush);
    // One drawLine per segment: drawLines() strokes all lines as one path, whose overlapping
    // outlines make the fill far slower.
    for (const QLineF& segment : wall_segments_) {
      QLineF clipped = segment;
      if (clipToRect(clipped, clip))
        p.drawLine(clipped);
    }
    p.restore();
  }

  if (layers.features) {
    constexpr double r = 4.0;
    for (const PointFeature& f : map_.features) {
      if (!finite(f.position))
        continue;
      const QPointF c = world.map(QPointF(f.position.x(), f.position.y()));
      if (f.kind == PointFeatureKind::kCorner) {
        // Concave corner: a small triangle.
        p.setPen(cosmeticPen(kCornerColour.darker(130), 1.0));
        p.setBrush(kCornerColour);
        p.drawPolygon(
            QPolygonF{c + QPointF(0, -r - 1), c + QPointF(r + 1, r), c + QPointF(-r - 1, r)});
      } else {
        // Convex edge: a diamond.
        p.setPen(cosmeticPen(kEdgeColour.darker(130), 1.0));
        p.setBrush(kEdgeColour);
        p.drawPolygon(QPolygonF{c + QPointF(0, -r), c + QPointF(r, 0), c + QPointF(0, r),
                                c + QPointF(-r, 0)});
      }
    }
  }

  if (layers.graph) {
    std::unordered_map<std::string, QPointF> node_px;
    for (const TopoNode& n : map_.graph.nodes) {
      if (finite(n.position))
        node_px[n.id] = world.map(QPointF(n.position.x(), n.position.y()));
    }
    p.setPen(cosmeticPen(kGraphColour, 1.6));
    p.setBrush(kGraphColour);
    for (const TopoEdge& e : map_.graph.edges) {
      const auto a = node_px.find(e.from), b = node_px.find(e.to);
      if (a == node_px.end() || b == node_px.end())
        continue;
      p.drawLine(a->second, b->second);
      if (!e.bidirectional) {  // arrowhead at the middle, pointing to `to`
        const QPointF d = b->second - a->second;
        const double len = std::hypot(d.x(), d.y());
        if (len > 20.0) {
          const QPointF u = d / len, n(-u.y(), u.x());
          const QPointF tip = (a->second + b->second) / 2.0 + u * 5.0;
          p.drawPolygon(QPolygonF{tip, tip - u * 9.0 + n * 4.5, tip - u * 9.0 - n * 4.5});
        }
      }
    }
    const bool labels = scale >= 8.0 || map_.graph.nodes.size() <= 40;
    QFont font = p.font();
    font.setPointSizeF(7.5);
    p.setFont(font);
    for (const TopoNode& n : map_.graph.nodes) {
      const auto it = node_px.find(n.id);
      if (it == node_px.end())
        continue;
      p.setPen(cosmeticPen(kGraphColour.darker(120), 2.0));
      p.setBrush(Qt::white);
      p.drawEllipse(it->second, 5.0, 5.0);
      if (!n.marker_id.empty()) {  // a node with a ceiling marker: red centre
        p.setPen(Qt::NoPen);
        p.setBrush(kMarkerOutline);
        p.drawEllipse(it->second, 2.2, 2.2);
      }
      if (labels) {
        p.setPen(kGraphLabel);
        p.drawText(it->second + QPointF(7, -6), QString::fromStdString(n.id));
      }
    }
  }
}

}  // namespace irgs::widgets
