#include "widgets/canvas/map_canvas.hpp"

#include <QKeyEvent>
#include <QLineF>
#include <QMouseEvent>
#include <QPainter>
#include <QWheelEvent>
#include <algorithm>
#include <cmath>
#include <utility>

#include "widgets/canvas/canvas_palette.hpp"
#include "widgets/canvas/finite_geometry.hpp"
#include "widgets/canvas/metric_overlays.hpp"

namespace irgs::widgets {
namespace {

constexpr double kFitPadding_px = 24.0;
constexpr double kDefaultScale = 50.0;

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
  map_layers_.setMap(map);
  invalidateCache();
  update();
}

void MapCanvas::setRobotProfile(const RobotProfile& profile) {
  robot_.setProfile(profile);
  sonar_.assign(robot_.profile().sonars.size(), std::nullopt);
  update();
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

void MapCanvas::setPlanningOverlay(PlanningOverlay overlay) {
  overlay_ = std::move(overlay);
  update();
}

void MapCanvas::setNavigationOverlay(NavigationOverlay overlay) {
  navigation_overlay_ = std::move(overlay);
  update();
}

void MapCanvas::setEstimatorOverlay(EstimatorOverlay overlay) {
  estimator_overlay_ = std::move(overlay);
  update();
}

void MapCanvas::setInteraction(Interaction interaction) {
  if (interaction == interaction_)
    return;
  interaction_ = interaction;
  region_from_.reset();
  setCursor(interaction_ == Interaction::kNavigate ? Qt::CrossCursor : Qt::PointingHandCursor);
  update();
  emit interactionChanged(interaction_);
}

void MapCanvas::clearTrail() {
  trail_.clear();
  trail_cache_.invalidate();
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
  grid_tiles_.clear();
  if (grid_) {
    blitGridCells(grid_->observedCellRect());
  }
  update();
}

void MapCanvas::blitGridCells(OccupancyGrid::CellRect cells) {
  if (!grid_ || cells.empty())
    return;
  cells = grid_tiles_.blit(*grid_, cells);
  if (cells.empty())
    return;

  // Repaint only the part of the widget the cells cover.
  const double res = grid_->resolution_m();
  const Vec2 c0 = grid_->cellCentre({cells.col0, cells.row0});
  const Vec2 c1 = grid_->cellCentre({cells.col1, cells.row1});
  const QPointF a = worldToWidget(c0 - Vec2(res, res));
  const QPointF b = worldToWidget(c1 + Vec2(res, res));
  update(QRectF(a, b).normalized().toAlignedRect().adjusted(-2, -2, 2, 2));
}

// ---- View ------------------------------------------------------------------------------------

MapView MapCanvas::view() const {
  return {centre_, scale_, size()};
}

QPointF MapCanvas::worldToWidget(const Vec2& p) const {
  return view().worldToWidget(p);
}

Vec2 MapCanvas::widgetToWorld(const QPointF& p) const {
  return view().widgetToWorld(p);
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
  const Box2 map_box = map_layers_.map().bounds();
  if (finite(map_box))
    box.extend(map_box);
  if (grid_) {
    const Box2 grid_box = grid_->observedBounds();
    if (finite(grid_box))
      box.extend(grid_box);
  }
  const double r = robot_.bodyRadius();
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

StaticLayerVisibility MapCanvas::staticLayers() const {
  return {layerVisible(Layer::kRaster), layerVisible(Layer::kWalls), layerVisible(Layer::kFeatures),
          layerVisible(Layer::kCeiling), layerVisible(Layer::kGraph)};
}

void MapCanvas::invalidateCache() {
  layer_cache_.invalidate();
}

void MapCanvas::viewWasChanged() {
  update();
  emit viewChanged();
}

void MapCanvas::stopAutoFit() {
  auto_fit_ = false;
}

// ---- Painting --------------------------------------------------------------------------------

void MapCanvas::paintEvent(QPaintEvent* /*event*/) {
  QPainter p(this);
  const MapView v = view();
  if (layer_cache_.ensure(v, devicePixelRatioF(), map_layers_, staticLayers()))
    trail_cache_.invalidate();
  const QPoint at = layer_cache_.topLeftIn(v);
  p.drawPixmap(at, layer_cache_.under());
  if (layerVisible(Layer::kGrid) && grid_)
    grid_tiles_.paint(p, *grid_, v);
  p.drawPixmap(at, layer_cache_.over());

  p.setRenderHint(QPainter::Antialiasing, true);
  if (layerVisible(Layer::kTrail)) {
    trail_cache_.update(trail_, trail_pushed_, layer_cache_.toCache(), layer_cache_.under());
    // One uniform translucency for overlapping strokes.
    p.setOpacity(palette::kTrailColour.alphaF());
    p.drawPixmap(at, trail_cache_.pixmap());
    p.setOpacity(1.0);
  }
  if (!overlay_.empty())
    paintPlanningOverlay(p, v, overlay_);
  if (layerVisible(Layer::kSonar) && pose_)
    robot_.paintSonar(p, v, *pose_, sonar_, last_time_s_, kSonarStale_s);
  if (layerVisible(Layer::kTruth) && true_pose_)
    robot_.paintRobot(p, v, *true_pose_, bumpers_, true);
  if (pose_)
    robot_.paintRobot(p, v, *pose_, bumpers_, false);
  if (!navigation_overlay_.empty())
    paintNavigationOverlay(p, v, navigation_overlay_);
  if (!estimator_overlay_.empty())
    paintEstimatorOverlay(p, v, estimator_overlay_);
  if (region_from_)
    paintRegionRubberBand(p, v, *region_from_, region_to_);
  paintScaleBar(p, scale_, height());
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
  if (event->button() == Qt::LeftButton && interaction_ == Interaction::kSelectRegion) {
    region_from_ = widgetToWorld(event->position());
    region_to_ = *region_from_;
    event->accept();
    return;
  }
  if (event->button() == Qt::LeftButton)
    press_pos_ = event->position();
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
  if (region_from_) {
    region_to_ = widgetToWorld(pos);
    update();
  }
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
  if (region_from_ && event->button() == Qt::LeftButton) {
    const Vec2 a = *region_from_;
    const Vec2 b = widgetToWorld(event->position());
    region_from_.reset();
    update();
    const double min_size_px = 2.0 * kClickSlop_px;
    if (std::abs(a.x() - b.x()) * scale_ >= min_size_px &&
        std::abs(a.y() - b.y()) * scale_ >= min_size_px) {
      emit regionSelected(std::min(a.x(), b.x()), std::min(a.y(), b.y()), std::max(a.x(), b.x()),
                          std::max(a.y(), b.y()));
    }
    event->accept();
    return;
  }
  if (event->button() == Qt::LeftButton && interaction_ == Interaction::kPickGoal &&
      QLineF(press_pos_, event->position()).length() <= kClickSlop_px) {
    dragging_ = false;
    setCursor(Qt::PointingHandCursor);
    const Vec2 w = widgetToWorld(event->position());
    emit worldClicked(w.x(), w.y());
    event->accept();
    return;
  }
  if (dragging_ && (event->button() == Qt::LeftButton || event->button() == Qt::MiddleButton)) {
    dragging_ = false;
    setCursor(interaction_ == Interaction::kNavigate ? Qt::CrossCursor : Qt::PointingHandCursor);
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
    case Qt::Key_Escape:
      if (interaction_ == Interaction::kNavigate) {
        QWidget::keyPressEvent(event);
        return;
      }
      setInteraction(Interaction::kNavigate);
      break;
    default:
      QWidget::keyPressEvent(event);
      return;
  }
  event->accept();
}

}  // namespace irgs::widgets
