#include "widgets/canvas/map_canvas.hpp"

#include <QKeyEvent>
#include <QMouseEvent>
#include <QPainter>
#include <QWheelEvent>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <unordered_map>

#include "widgets/canvas/grid_image.hpp"

namespace irgs::widgets {
namespace {

// Palette (sRGB). Static layers are light and quiet; live data is saturated.
const QColor kOutsideColour(236, 238, 242);
const QColor kFloorColour(252, 252, 250);
const QColor kMinorGridColour(232, 234, 238);
const QColor kMajorGridColour(212, 216, 223);
const QColor kWallColour(44, 49, 60);
const QColor kObstacleFill(196, 201, 209);
const QColor kObstacleOutline(112, 119, 131);
const QColor kCornerColour(239, 108, 0);
const QColor kEdgeColour(126, 87, 194);
const QColor kMarkerFill(229, 57, 53, 70);
const QColor kMarkerOutline(229, 57, 53, 130);
const QColor kLightFill(255, 236, 140, 110);
const QColor kLightOutline(214, 184, 60, 120);
const QColor kGraphColour(25, 118, 210, 190);
const QColor kGraphLabel(13, 71, 161);
const QColor kRobotFill(30, 136, 229, 215);
const QColor kRobotOutline(13, 71, 161);
const QColor kTruthColour(46, 160, 67);
const QColor kTrailColour(142, 36, 170, 150);  // purple: apart from the graph blue
const QColor kEchoFill(255, 152, 0, 50);
const QColor kEchoOutline(230, 120, 0, 150);
const QColor kEchoArc(216, 67, 21, 230);
const QColor kNoEchoFill(120, 144, 156, 28);
const QColor kNoEchoOutline(120, 144, 156, 110);
const QColor kBumperIdle(55, 60, 70, 150);
const QColor kBumperHit(229, 28, 35);

constexpr int kCacheMargin_px = 256;  // static layers extend this far beyond the viewport
constexpr double kFitPadding_px = 24.0;
constexpr double kDefaultScale = 50.0;
constexpr double kFallbackBodyRadius_m = 0.15;
constexpr double kMinRobotRadius_px = 7.0;  // below this the robot is drawn as a fixed marker

bool finite(const Vec2& p) {
  return std::isfinite(p.x()) && std::isfinite(p.y());
}
bool finite(const Pose2& p) {
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.theta);
}
bool finite(const Box2& b) {
  return !b.empty() && finite(b.min) && finite(b.max);
}

// The largest 1-2-5 step not longer than `limit` (> 0); `leading` receives 1, 2 or 5.
double niceStepBelow(double limit, int* leading = nullptr) {
  const double decade = std::pow(10.0, std::floor(std::log10(limit)));
  int lead = 1;
  if (5.0 * decade <= limit)
    lead = 5;
  else if (2.0 * decade <= limit)
    lead = 2;
  if (leading)
    *leading = lead;
  return lead * decade;
}

// The smallest 1-2-5 step at least `limit` (> 0).
double niceStepAbove(double limit, int* leading) {
  const double decade = std::pow(10.0, std::floor(std::log10(limit)));
  for (int lead : {1, 2, 5}) {
    if (lead * decade >= limit * (1.0 - 1e-9)) {
      *leading = lead;
      return lead * decade;
    }
  }
  *leading = 1;
  return 10.0 * decade;
}

QString lengthLabel(double metres) {
  if (metres >= 1000.0)
    return QStringLiteral("%1 km").arg(metres / 1000.0);
  if (metres >= 1.0)
    return QStringLiteral("%1 m").arg(metres);
  if (metres >= 0.01)
    return QStringLiteral("%1 cm").arg(std::round(metres * 1000.0) / 10.0);
  return QStringLiteral("%1 mm").arg(std::round(metres * 10000.0) / 10.0);
}

QPen cosmeticPen(const QColor& colour, double width_px, Qt::PenStyle style = Qt::SolidLine) {
  QPen pen(colour, width_px, style, Qt::RoundCap, Qt::RoundJoin);
  pen.setCosmetic(true);
  return pen;
}

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

std::int64_t tileKey(int tx, int ty) {
  return (static_cast<std::int64_t>(tx) << 32) | static_cast<std::uint32_t>(ty);
}

// Floor division for tile indices of negative cells.
int floorDiv(int a, int b) {
  return a >= 0 ? a / b : -((-a + b - 1) / b);
}

}  // namespace

MapCanvas::MapCanvas(QWidget* parent) : QWidget(parent) {
  setMouseTracking(true);
  setFocusPolicy(Qt::WheelFocus);
  setAttribute(Qt::WA_OpaquePaintEvent);
  setCursor(Qt::CrossCursor);
}

MapCanvas::~MapCanvas() = default;

// ---- Content ---------------------------------------------------------------------------------

void MapCanvas::setWorldMap(const WorldMap& map) {
  map_ = map;
  rebuildMapGeometry();
  invalidateCache();
  update();
}

void MapCanvas::rebuildMapGeometry() {
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
  }

  raster_image_ = map_.raster ? rasterToImage(map_.raster->raster) : QImage();
}

void MapCanvas::setRobotProfile(const RobotProfile& profile) {
  profile_ = profile;
  body_polygon_.clear();
  for (const Vec2& p : profile_.body_outline) {
    if (finite(p))
      body_polygon_ << QPointF(p.x(), p.y());
  }
  if (body_polygon_.size() < 3)
    body_polygon_.clear();  // drawn as a disc of kFallbackBodyRadius_m
  sonar_.assign(profile_.sonars.size(), std::nullopt);
  update();
}

double MapCanvas::bodyRadius() const {
  if (body_polygon_.isEmpty())
    return kFallbackBodyRadius_m;
  double r = 0.0;
  for (const QPointF& p : body_polygon_)
    r = std::max(r, std::hypot(p.x(), p.y()));
  return r > 0.0 ? r : kFallbackBodyRadius_m;
}

void MapCanvas::setRobotState(const TelemetrySample& s) {
  if (!finite(s.odometry_pose))
    return;
  if (s.time_s < last_time_s_)  // a new run: old readings belong to another timeline
    std::fill(sonar_.begin(), sonar_.end(), std::nullopt);
  last_time_s_ = std::isfinite(s.time_s) ? s.time_s : last_time_s_;

  pose_ = s.odometry_pose;
  true_pose_ = (s.true_pose && finite(*s.true_pose)) ? s.true_pose : std::nullopt;
  bumpers_ = s.bumpers;
  for (const SonarReading& reading : s.sonar) {
    if (reading.sensor < 0 || static_cast<std::size_t>(reading.sensor) >= sonar_.size())
      continue;
    if (reading.echo && !std::isfinite(reading.range_m))
      continue;
    sonar_[static_cast<std::size_t>(reading.sensor)] = SonarState{reading, last_time_s_};
  }

  const Vec2 p = pose_->position();
  if (trail_.empty() || (p - trail_.back()).norm() >= kTrailStep_m) {
    trail_.push_back(p);
    ++trail_pushed_;
    while (trail_.size() > kMaxTrailPoints)
      trail_.pop_front();
  }

  if (follow_robot_ && (centre_ - p).norm() * scale_ >= 0.5) {
    centre_ = p;
    viewWasChanged();
  }
  update();
}

void MapCanvas::clearTrail() {
  trail_.clear();
  cache_.trail_valid = false;
  update();
}

// ---- Occupancy grid --------------------------------------------------------------------------

void MapCanvas::setGrid(OccupancyGrid* grid) {
  mutable_grid_ = grid;
  grid_ = grid;
  if (mutable_grid_)
    mutable_grid_->takeDirtyRect();  // everything is drawn below
  redrawWholeGrid();
}

void MapCanvas::setGrid(const OccupancyGrid* grid) {
  mutable_grid_ = nullptr;
  grid_ = grid;
  redrawWholeGrid();
}

void MapCanvas::setGrid(std::nullptr_t) {
  setGrid(static_cast<const OccupancyGrid*>(nullptr));
}

void MapCanvas::gridUpdated() {
  if (mutable_grid_)
    blitGridCells(mutable_grid_->takeDirtyRect());
  else
    redrawWholeGrid();
}

void MapCanvas::gridUpdated(const OccupancyGrid::CellRect& dirty_cells) {
  blitGridCells(dirty_cells);
}

void MapCanvas::redrawWholeGrid() {
  tiles_.clear();
  if (grid_) {
    blitGridCells(grid_->observedCellRect());
  }
  update();
}

void MapCanvas::blitGridCells(OccupancyGrid::CellRect cells) {
  if (!grid_ || cells.empty())
    return;
  // Never trust a dirty rect beyond what the grid has observed (a runaway rect must not make
  // us allocate or loop over nothing).
  const OccupancyGrid::CellRect observed = grid_->observedCellRect();
  cells.col0 = std::max(cells.col0, observed.col0);
  cells.row0 = std::max(cells.row0, observed.row0);
  cells.col1 = std::min(cells.col1, observed.col1);
  cells.row1 = std::min(cells.row1, observed.row1);
  if (cells.empty())
    return;

  const int tx0 = floorDiv(cells.col0, kTileCells), tx1 = floorDiv(cells.col1, kTileCells);
  const int ty0 = floorDiv(cells.row0, kTileCells), ty1 = floorDiv(cells.row1, kTileCells);
  for (int ty = ty0; ty <= ty1; ++ty) {
    for (int tx = tx0; tx <= tx1; ++tx) {
      const int tile_col0 = tx * kTileCells, tile_row0 = ty * kTileCells;
      const OccupancyGrid::CellRect part{std::max(cells.col0, tile_col0),
                                         std::max(cells.row0, tile_row0),
                                         std::min(cells.col1, tile_col0 + kTileCells - 1),
                                         std::min(cells.row1, tile_row0 + kTileCells - 1)};
      const QImage piece = gridToImage(*grid_, part);
      if (piece.isNull())
        continue;
      GridTile& tile = tiles_[tileKey(tx, ty)];
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

  // Repaint only the part of the widget the cells cover.
  const double res = grid_->resolution_m();
  const Vec2 c0 = grid_->cellCentre({cells.col0, cells.row0});
  const Vec2 c1 = grid_->cellCentre({cells.col1, cells.row1});
  const QPointF a = worldToWidget(c0 - Vec2(res, res));
  const QPointF b = worldToWidget(c1 + Vec2(res, res));
  update(QRectF(a, b).normalized().toAlignedRect().adjusted(-2, -2, 2, 2));
}

void MapCanvas::paintGrid(QPainter& p) const {
  if (!grid_ || tiles_.empty())
    return;
  const double res = grid_->resolution_m();
  const double cell_px = res * scale_;
  const bool use_reduced = cell_px * kTileMipFactor < 2.0;
  p.save();
  p.setRenderHint(QPainter::Antialiasing, false);
  // Crisp cells when zoomed in, filtered when cells are smaller than a pixel.
  p.setRenderHint(QPainter::SmoothPixmapTransform, cell_px < 1.0);

  // Visible tile range.
  const Vec2 w0 = widgetToWorld(QPointF(0, height()));
  const Vec2 w1 = widgetToWorld(QPointF(width(), 0));
  const Cell c0 = grid_->cellAt(w0), c1 = grid_->cellAt(w1);
  const int tx0 = floorDiv(c0.col, kTileCells), tx1 = floorDiv(c1.col, kTileCells);
  const int ty0 = floorDiv(c0.row, kTileCells), ty1 = floorDiv(c1.row, kTileCells);
  const bool iterate_map = static_cast<long long>(tx1 - tx0 + 1) * (ty1 - ty0 + 1) >
                           static_cast<long long>(tiles_.size());

  auto draw = [&](std::int64_t key, GridTile& tile) {
    const int tx = static_cast<int>(key >> 32);
    const int ty = static_cast<int>(static_cast<std::int32_t>(key & 0xffffffff));
    if (tx < tx0 || tx > tx1 || ty < ty0 || ty > ty1)
      return;
    const Vec2 corner = grid_->cellCentre({tx * kTileCells, ty * kTileCells}) -
                        Vec2(res / 2.0, res / 2.0);  // lower-left of the tile
    const double span = kTileCells * res;
    const QRectF target(worldToWidget(Vec2(corner.x(), corner.y() + span)),
                        worldToWidget(Vec2(corner.x() + span, corner.y())));
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

// ---- View ------------------------------------------------------------------------------------

QTransform MapCanvas::worldTransform() const {
  return {scale_,
          0.0,
          0.0,
          -scale_,
          width() / 2.0 - centre_.x() * scale_,
          height() / 2.0 + centre_.y() * scale_};
}

QPointF MapCanvas::worldToWidget(const Vec2& p) const {
  return {width() / 2.0 + (p.x() - centre_.x()) * scale_,
          height() / 2.0 - (p.y() - centre_.y()) * scale_};
}

Vec2 MapCanvas::widgetToWorld(const QPointF& p) const {
  return {centre_.x() + (p.x() - width() / 2.0) / scale_,
          centre_.y() - (p.y() - height() / 2.0) / scale_};
}

void MapCanvas::setView(const Vec2& centre, double pixels_per_metre) {
  if (finite(centre))
    centre_ = centre;
  if (std::isfinite(pixels_per_metre))
    scale_ = std::clamp(pixels_per_metre, kMinPixelsPerMetre, kMaxPixelsPerMetre);
  stopAutoFit();
  viewWasChanged();
}

void MapCanvas::zoomAt(const QPointF& anchor, double factor) {
  if (!std::isfinite(factor) || factor <= 0.0)
    return;
  const Vec2 fixed = widgetToWorld(anchor);
  stopAutoFit();
  scale_ = std::clamp(scale_ * factor, kMinPixelsPerMetre, kMaxPixelsPerMetre);
  centre_ = {fixed.x() - (anchor.x() - width() / 2.0) / scale_,
             fixed.y() + (anchor.y() - height() / 2.0) / scale_};
  viewWasChanged();
}

Box2 MapCanvas::contentBounds() const {
  Box2 box;
  const Box2 map_box = map_.bounds();
  if (finite(map_box))
    box.extend(map_box);
  if (grid_) {
    const Box2 grid_box = grid_->observedBounds();
    if (finite(grid_box))
      box.extend(grid_box);
  }
  const double r = bodyRadius();
  for (const auto& pose : {pose_, true_pose_}) {
    if (pose) {
      box.extend(Vec2(pose->x - r, pose->y - r));
      box.extend(Vec2(pose->x + r, pose->y + r));
    }
  }
  return box;
}

void MapCanvas::zoomToFit() {
  const Box2 box = contentBounds();
  auto_fit_ = true;
  if (box.empty()) {
    centre_ = Vec2::Zero();
    scale_ = kDefaultScale;
    viewWasChanged();
    return;
  }
  const double w = std::max(width() - 2.0 * kFitPadding_px, 10.0);
  const double h = std::max(height() - 2.0 * kFitPadding_px, 10.0);
  const Vec2 size = box.size();
  double s = kDefaultScale;
  if (size.x() > 1e-9 && size.y() > 1e-9)
    s = std::min(w / size.x(), h / size.y());
  else if (size.x() > 1e-9)
    s = w / size.x();
  else if (size.y() > 1e-9)
    s = h / size.y();
  scale_ = std::clamp(s, kMinPixelsPerMetre, kMaxPixelsPerMetre);
  centre_ = (box.min + box.max) / 2.0;
  viewWasChanged();
}

void MapCanvas::setFollowRobot(bool follow) {
  if (follow == follow_robot_)
    return;
  follow_robot_ = follow;
  if (follow_robot_ && pose_) {
    centre_ = pose_->position();
    viewWasChanged();
  }
  emit followRobotChanged(follow_robot_);
}

void MapCanvas::setLayerVisible(Layer layer, bool visible) {
  const unsigned bit = 1u << static_cast<unsigned>(layer);
  const unsigned layers = visible ? (layers_ | bit) : (layers_ & ~bit);
  if (layers == layers_)
    return;
  layers_ = layers;
  invalidateCache();
  update();
}

bool MapCanvas::layerVisible(Layer layer) const {
  return (layers_ & (1u << static_cast<unsigned>(layer))) != 0;
}

void MapCanvas::invalidateCache() {
  cache_.valid = false;
}

void MapCanvas::viewWasChanged() {
  update();
  emit viewChanged();
}

void MapCanvas::stopAutoFit() {
  auto_fit_ = false;
}

// ---- Static layers ---------------------------------------------------------------------------

void MapCanvas::ensureCache() {
  const double dpr = devicePixelRatioF();
  const QPointF offset = worldToWidget(cache_.origin);
  const bool covers = offset.x() <= 0.5 && offset.y() <= 0.5 &&
                      offset.x() + cache_.size.width() >= width() - 0.5 &&
                      offset.y() + cache_.size.height() >= height() - 0.5;
  if (cache_.valid && cache_.scale == scale_ && covers && cache_.under.devicePixelRatio() == dpr)
    return;

  cache_.scale = scale_;
  cache_.size = size() + QSize(2 * kCacheMargin_px, 2 * kCacheMargin_px);
  cache_.origin = widgetToWorld(QPointF(-kCacheMargin_px, -kCacheMargin_px));
  const QSize device_size = (QSizeF(cache_.size) * dpr).toSize();
  const QTransform world(scale_, 0.0, 0.0, -scale_, -cache_.origin.x() * scale_,
                         cache_.origin.y() * scale_);
  const QRectF world_rect(cache_.origin.x(), cache_.origin.y() - cache_.size.height() / scale_,
                          cache_.size.width() / scale_, cache_.size.height() / scale_);

  cache_.under = QPixmap(device_size);
  cache_.under.setDevicePixelRatio(dpr);
  {
    QPainter p(&cache_.under);
    renderUnder(p, world, world_rect);
  }
  cache_.over = QPixmap(device_size);
  cache_.over.setDevicePixelRatio(dpr);
  cache_.over.fill(Qt::transparent);
  {
    QPainter p(&cache_.over);
    renderOver(p, world, world_rect);
  }
  cache_.valid = true;
  cache_.trail_valid = false;
}

void MapCanvas::renderUnder(QPainter& p, const QTransform& world, const QRectF& world_rect) const {
  const QRectF all(QPointF(0, 0), QSizeF(cache_.size));
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

  renderMetricGrid(p, world, world_rect);

  if (layerVisible(Layer::kRaster) && !raster_image_.isNull() && map_.raster) {
    const RasterMap& r = map_.raster->raster;
    // Image pixel (u, v) -> world (ox + u res, oy + (H - v) res); the origin yaw is ignored
    // like ROS does (see raster_map.hpp).
    const QTransform image_to_world(r.resolution_m, 0.0, 0.0, -r.resolution_m, r.origin.x,
                                    r.origin.y + r.height * r.resolution_m);
    p.save();
    p.setTransform(image_to_world * world);
    p.setRenderHint(QPainter::SmoothPixmapTransform, r.resolution_m * scale_ < 2.0);
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

void MapCanvas::renderMetricGrid(QPainter& p, const QTransform& world,
                                 const QRectF& world_rect) const {
  int leading = 1;
  const double step = niceStepAbove(40.0 / scale_, &leading);  // >= 40 px between lines
  const int major_every = leading == 5 ? 2 : 5;                // major lines at 5, 10 or 10 x 10^k
  p.save();
  p.setRenderHint(QPainter::Antialiasing, false);
  const double x0 = world_rect.left(), x1 = world_rect.right();
  const double y0 = world_rect.top(), y1 = world_rect.bottom();  // world y0 < y1
  const auto first_x = static_cast<long long>(std::floor(x0 / step));
  const auto last_x = static_cast<long long>(std::ceil(x1 / step));
  const auto first_y = static_cast<long long>(std::floor(y0 / step));
  const auto last_y = static_cast<long long>(std::ceil(y1 / step));
  const double top = 0.0, bottom = cache_.size.height();
  const double left = 0.0, right = cache_.size.width();
  for (int pass = 0; pass < 2; ++pass) {  // minor lines first, major on top
    const bool major_pass = pass == 1;
    p.setPen(QPen(major_pass ? kMajorGridColour : kMinorGridColour, 1.0));
    for (long long i = first_x; i <= last_x; ++i) {
      if ((i % major_every == 0) != major_pass)
        continue;
      const double x = std::round(world.map(QPointF(static_cast<double>(i) * step, 0)).x()) + 0.5;
      p.drawLine(QPointF(x, top), QPointF(x, bottom));
    }
    for (long long i = first_y; i <= last_y; ++i) {
      if ((i % major_every == 0) != major_pass)
        continue;
      const double y = std::round(world.map(QPointF(0, static_cast<double>(i) * step)).y()) + 0.5;
      p.drawLine(QPointF(left, y), QPointF(right, y));
    }
  }
  p.restore();
}

void MapCanvas::renderOver(QPainter& p, const QTransform& world, const QRectF& world_rect) const {
  p.setRenderHint(QPainter::Antialiasing, true);

  if (layerVisible(Layer::kCeiling)) {
    p.save();
    p.setTransform(world);
    p.setPen(cosmeticPen(kLightOutline, 1.0));
    p.setBrush(kLightFill);
    p.drawPath(light_path_);
    p.setPen(cosmeticPen(kMarkerOutline, 1.0));
    p.setBrush(kMarkerFill);
    for (const QPolygonF& square : marker_polygons_)
      p.drawPolygon(square);
    p.restore();
  }

  if (layerVisible(Layer::kWalls)) {
    p.save();
    p.setTransform(world);
    p.setPen(cosmeticPen(kObstacleOutline, 1.2));
    p.setBrush(kObstacleFill);
    for (const QPolygonF& polygon : obstacle_polygons_)
      p.drawPolygon(polygon);
    // Walls are drawn about 5 cm thick, but never thinner than 2 px nor thicker than 8 px.
    const double wall_px = std::clamp(0.05 * scale_, 2.0, 8.0);
    p.setPen(cosmeticPen(kWallColour, wall_px));
    // Segments are clipped to the cached area (plus the pen) before stroking: a long wall
    // crossing the view at a high zoom would otherwise be stroked over its whole length.
    const double pad = wall_px / scale_;
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

  if (layerVisible(Layer::kFeatures)) {
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

  if (layerVisible(Layer::kGraph)) {
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
    const bool labels = scale_ >= 8.0 || map_.graph.nodes.size() <= 40;
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

// ---- Dynamic layers --------------------------------------------------------------------------

QTransform MapCanvas::cacheTransform() const {
  return {cache_.scale,
          0.0,
          0.0,
          -cache_.scale,
          -cache_.origin.x() * cache_.scale,
          cache_.origin.y() * cache_.scale};
}

void MapCanvas::updateTrailCache() {
  // The trail only grows at its end: new segments are stroked onto the cached pixmap; the whole
  // trail is redrawn when the cache moves, or when enough old points were dropped from its
  // start that the pixmap would show a visibly longer trail than kMaxTrailPoints.
  constexpr std::uint64_t kRedrawAfterDropped = 1000;
  const std::uint64_t dropped = trail_pushed_ - trail_.size();
  const bool whole = !cache_.trail_valid || cache_.trail_upto < dropped + 1 ||
                     dropped - cache_.trail_dropped_at >= kRedrawAfterDropped;
  if (!whole && cache_.trail_upto == trail_pushed_)
    return;
  if (whole) {
    cache_.trail = QPixmap(cache_.under.size());
    cache_.trail.setDevicePixelRatio(cache_.under.devicePixelRatio());
    cache_.trail.fill(Qt::transparent);
    cache_.trail_dropped_at = dropped;
  }
  const std::size_t first =
      whole ? 0 : static_cast<std::size_t>(cache_.trail_upto - dropped - 1);  // last drawn point
  cache_.trail_valid = true;
  cache_.trail_upto = trail_pushed_;
  if (trail_.size() < first + 2)
    return;

  const QTransform to_cache = cacheTransform();
  QPainter p(&cache_.trail);
  p.setRenderHint(QPainter::Antialiasing, true);
  QPen pen =
      cosmeticPen(QColor(kTrailColour.red(), kTrailColour.green(), kTrailColour.blue()), 2.0);
  p.setPen(pen);
  // Points closer than a pixel add nothing but cost; long polylines are stroked in pieces
  // (the stroker's cost grows faster than linearly with the vertex count).
  constexpr qsizetype kPiece = 256;
  QPolygonF line;
  line.reserve(kPiece + 1);
  QPointF last;
  for (std::size_t i = first; i < trail_.size(); ++i) {
    const QPointF q = to_cache.map(QPointF(trail_[i].x(), trail_[i].y()));
    const bool is_last = i + 1 == trail_.size();
    if (!line.isEmpty() && !is_last &&
        std::abs(q.x() - last.x()) + std::abs(q.y() - last.y()) < 1.5)
      continue;
    line << q;
    last = q;
    if (line.size() > kPiece) {
      p.drawPolyline(line);
      line.clear();
      line << q;
    }
  }
  if (line.size() >= 2)
    p.drawPolyline(line);
}

void MapCanvas::paintSonar(QPainter& p) const {
  if (!pose_)
    return;
  for (std::size_t i = 0; i < sonar_.size() && i < profile_.sonars.size(); ++i) {
    if (!sonar_[i] || last_time_s_ - sonar_[i]->time_s > kSonarStale_s)
      continue;
    const SonarSpec& spec = profile_.sonars[i];
    const SonarReading& r = sonar_[i]->reading;
    const double range =
        r.echo ? std::clamp(r.range_m, 0.0, std::max(spec.max_range_m, 0.0)) : spec.max_range_m;
    if (!std::isfinite(range) || !finite(spec.mount) || range * scale_ < 1.0)
      continue;
    const Pose2 mount = pose_->compose(spec.mount);
    const QPointF apex = worldToWidget(mount.position());
    const double radius = range * scale_;
    const double width_deg = std::clamp(radToDeg(spec.beam_width_rad), 0.5, 360.0);
    const double start_deg = radToDeg(mount.theta) - width_deg / 2.0;  // Qt: CCW on screen
    const QRectF box(apex - QPointF(radius, radius), QSizeF(2 * radius, 2 * radius));
    QPainterPath cone(apex);
    cone.arcTo(box, start_deg, width_deg);
    cone.closeSubpath();
    if (r.echo) {
      p.setPen(cosmeticPen(kEchoOutline, 1.0));
      p.setBrush(kEchoFill);
      p.drawPath(cone);
      QPainterPath arc;
      arc.arcMoveTo(box, start_deg);
      arc.arcTo(box, start_deg, width_deg);
      p.setPen(cosmeticPen(kEchoArc, 2.5));
      p.setBrush(Qt::NoBrush);
      p.drawPath(arc);
    } else {
      p.setPen(cosmeticPen(kNoEchoOutline, 1.0, Qt::DashLine));
      p.setBrush(kNoEchoFill);
      p.drawPath(cone);
    }
  }
}

void MapCanvas::paintRobot(QPainter& p, const Pose2& pose, bool ghost) const {
  const double radius = bodyRadius();
  const double c = std::cos(pose.theta), s = std::sin(pose.theta);
  p.save();
  if (radius * scale_ < kMinRobotRadius_px) {
    // Too small to show its shape: a fixed-size disc with a heading tick.
    const QPointF centre = worldToWidget(pose.position());
    const QPointF tip = centre + QPointF(c, -s) * (kMinRobotRadius_px + 5.0);
    if (ghost) {
      p.setPen(cosmeticPen(kTruthColour, 1.5, Qt::DashLine));
      p.setBrush(Qt::NoBrush);
    } else {
      p.setPen(cosmeticPen(kRobotOutline, 1.5));
      p.setBrush(kRobotFill);
    }
    p.drawEllipse(centre, kMinRobotRadius_px, kMinRobotRadius_px);
    p.drawLine(centre, tip);
    p.restore();
    return;
  }

  // Body frame -> world -> widget.
  p.setTransform(QTransform(c, s, -s, c, pose.x, pose.y) * worldTransform());
  if (ghost) {
    p.setPen(cosmeticPen(kTruthColour, 1.6, Qt::DashLine));
    p.setBrush(QColor(kTruthColour.red(), kTruthColour.green(), kTruthColour.blue(), 25));
  } else {
    p.setPen(cosmeticPen(kRobotOutline, 1.6));
    p.setBrush(kRobotFill);
  }
  if (body_polygon_.isEmpty())
    p.drawEllipse(QPointF(0, 0), radius, radius);
  else
    p.drawPolygon(body_polygon_);

  // Heading arrow (a chevron pointing along body +x).
  const double r = radius;
  const QPolygonF arrow{QPointF(0.72 * r, 0), QPointF(-0.3 * r, 0.42 * r), QPointF(-0.08 * r, 0),
                        QPointF(-0.3 * r, -0.42 * r)};
  if (ghost) {
    p.setBrush(Qt::NoBrush);
    p.drawPolygon(arrow);
  } else {
    p.setPen(cosmeticPen(QColor(255, 255, 255, 235), 1.0));
    p.setBrush(QColor(255, 255, 255, 235));
    p.drawPolygon(arrow);

    // Bumpers: a bar along the face at each bumper; red and thick when pressed.
    for (std::size_t i = 0; i < profile_.bumpers.size(); ++i) {
      const BumperSpec& b = profile_.bumpers[i];
      if (!finite(b.position) || !std::isfinite(b.normal_rad))
        continue;
      const bool pressed = i < 32 && (bumpers_ >> i) & 1u;
      const Vec2 tangent(-std::sin(b.normal_rad), std::cos(b.normal_rad));
      const double half = std::isfinite(b.half_width_m) ? std::max(b.half_width_m, 0.01) : 0.05;
      const Vec2 a = b.position - tangent * half, e = b.position + tangent * half;
      p.setPen(cosmeticPen(pressed ? kBumperHit : kBumperIdle, pressed ? 5.0 : 2.5));
      p.drawLine(QPointF(a.x(), a.y()), QPointF(e.x(), e.y()));
    }
  }
  p.restore();
}

void MapCanvas::paintScaleBar(QPainter& p) const {
  const double max_len_m = 140.0 / scale_;
  const double len_m = niceStepBelow(max_len_m);
  const double len_px = len_m * scale_;
  const QString label = lengthLabel(len_m);
  QFont font = p.font();
  font.setPointSizeF(8.5);
  p.setFont(font);
  const QFontMetricsF metrics(font);
  const double text_w = metrics.horizontalAdvance(label);
  const double left = 12.0, bottom = height() - 12.0;
  const QRectF panel(left - 6.0, bottom - 12.0 - metrics.height() - 6.0,
                     std::max(len_px, text_w) + 12.0, 12.0 + metrics.height() + 10.0);
  p.setPen(Qt::NoPen);
  p.setBrush(QColor(255, 255, 255, 200));
  p.drawRoundedRect(panel, 4.0, 4.0);
  p.setPen(QPen(QColor(33, 33, 33), 2.0, Qt::SolidLine, Qt::FlatCap));
  const double y = bottom - 4.0;
  p.drawLine(QPointF(left, y), QPointF(left + len_px, y));
  p.drawLine(QPointF(left, y - 5.0), QPointF(left, y + 1.0));
  p.drawLine(QPointF(left + len_px, y - 5.0), QPointF(left + len_px, y + 1.0));
  p.drawText(QRectF(left, panel.top() + 3.0, std::max(len_px, text_w), metrics.height()),
             Qt::AlignHCenter | Qt::AlignVCenter, label);
}

void MapCanvas::paintEvent(QPaintEvent* /*event*/) {
  QPainter p(this);
  ensureCache();
  const QPointF offset = worldToWidget(cache_.origin);
  const QPoint at(qRound(offset.x()), qRound(offset.y()));
  p.drawPixmap(at, cache_.under);
  if (layerVisible(Layer::kGrid))
    paintGrid(p);
  p.drawPixmap(at, cache_.over);

  p.setRenderHint(QPainter::Antialiasing, true);
  if (layerVisible(Layer::kTrail)) {
    updateTrailCache();
    p.setOpacity(kTrailColour.alphaF());  // one uniform translucency for overlapping strokes
    p.drawPixmap(at, cache_.trail);
    p.setOpacity(1.0);
  }
  if (layerVisible(Layer::kSonar))
    paintSonar(p);
  if (layerVisible(Layer::kTruth) && true_pose_)
    paintRobot(p, *true_pose_, true);
  if (pose_)
    paintRobot(p, *pose_, false);
  paintScaleBar(p);
}

// ---- Interaction -----------------------------------------------------------------------------

void MapCanvas::resizeEvent(QResizeEvent* event) {
  QWidget::resizeEvent(event);
  if (auto_fit_)
    zoomToFit();
  else
    viewWasChanged();
}

void MapCanvas::mousePressEvent(QMouseEvent* event) {
  if (event->button() == Qt::LeftButton || event->button() == Qt::MiddleButton) {
    dragging_ = true;
    last_mouse_ = event->position();
    setCursor(Qt::ClosedHandCursor);
    event->accept();
    return;
  }
  QWidget::mousePressEvent(event);
}

void MapCanvas::mouseMoveEvent(QMouseEvent* event) {
  const QPointF pos = event->position();
  if (dragging_) {
    const QPointF delta = pos - last_mouse_;
    last_mouse_ = pos;
    if (delta != QPointF(0, 0)) {
      stopAutoFit();
      if (follow_robot_) {
        follow_robot_ = false;
        emit followRobotChanged(false);
      }
      centre_ -= Vec2(delta.x() / scale_, -delta.y() / scale_);
      viewWasChanged();
    }
  }
  const Vec2 w = widgetToWorld(pos);
  emit cursorMoved(w.x(), w.y());
}

void MapCanvas::mouseReleaseEvent(QMouseEvent* event) {
  if (dragging_ && (event->button() == Qt::LeftButton || event->button() == Qt::MiddleButton)) {
    dragging_ = false;
    setCursor(Qt::CrossCursor);
    event->accept();
    return;
  }
  QWidget::mouseReleaseEvent(event);
}

void MapCanvas::mouseDoubleClickEvent(QMouseEvent* event) {
  if (event->button() == Qt::LeftButton) {
    zoomToFit();
    event->accept();
    return;
  }
  QWidget::mouseDoubleClickEvent(event);
}

void MapCanvas::wheelEvent(QWheelEvent* event) {
  const QPoint delta = event->angleDelta();
  const int steps = delta.y() != 0 ? delta.y() : delta.x();
  if (steps == 0) {
    event->ignore();
    return;
  }
  stopAutoFit();
  // 120 units = one notch = x1.2; following keeps the robot in the centre.
  const double factor = std::pow(1.2, steps / 120.0);
  const QPointF anchor = follow_robot_ ? QPointF(width() / 2.0, height() / 2.0) : event->position();
  zoomAt(anchor, factor);
  event->accept();
}

void MapCanvas::keyPressEvent(QKeyEvent* event) {
  const QPointF middle(width() / 2.0, height() / 2.0);
  switch (event->key()) {
    case Qt::Key_Home:
      zoomToFit();
      break;
    case Qt::Key_Plus:
    case Qt::Key_Equal:
      stopAutoFit();
      zoomAt(middle, 1.25);
      break;
    case Qt::Key_Minus:
      stopAutoFit();
      zoomAt(middle, 1.0 / 1.25);
      break;
    case Qt::Key_F:
      setFollowRobot(!follow_robot_);
      break;
    default:
      QWidget::keyPressEvent(event);
      return;
  }
  event->accept();
}

}  // namespace irgs::widgets
