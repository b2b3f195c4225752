#include "widgets/editor/editor_layer.hpp"

#include <QEvent>
#include <QFontMetricsF>
#include <QKeyEvent>
#include <QMouseEvent>
#include <QPainter>
#include <QPainterPath>
#include <QWheelEvent>
#include <cmath>

#include "core/editing/floor_plan.hpp"
#include "core/editing/hit_test.hpp"
#include "widgets/canvas/map_canvas.hpp"
#include "widgets/editor/editor_model.hpp"

namespace irgs::widgets {

using editing::ElementKind;
using editing::ElementRef;
using editing::SnapKind;

namespace {

const QColor kSelection(255, 140, 0);  // orange outline and handles
const QColor kDraft(0, 120, 215);      // blue outline being drawn
const QColor kMeasure(120, 40, 170);   // purple measure line
const QColor kIssueError(200, 30, 30);
const QColor kIssueWarning(230, 150, 0);

// The outline drawn for a selected marker or light: its square / tube rectangle.
std::vector<Vec2> rectangle(const Vec2& centre, double heading, double length, double width) {
  const Vec2 u(std::cos(heading), std::sin(heading));
  const Vec2 v(-u.y(), u.x());
  const Vec2 a = 0.5 * length * u, b = 0.5 * width * v;
  return {centre - a - b, centre + a - b, centre + a + b, centre - a + b};
}

bool isClosed(const editing::Element& e) {
  if (const auto* w = std::get_if<Wall>(&e))
    return w->closed;
  return std::holds_alternative<Obstacle>(e);
}

}  // namespace

EditorLayer::EditorLayer(MapCanvas& canvas, EditorModel& model)
    : QWidget(&canvas), canvas_(canvas), model_(model) {
  setObjectName(QStringLiteral("editorLayer"));
  setMouseTracking(true);
  setFocusPolicy(Qt::StrongFocus);
  setGeometry(canvas.rect());
  canvas.installEventFilter(this);
  connect(&canvas, &MapCanvas::viewChanged, this, qOverload<>(&QWidget::update));
  connect(&model, &EditorModel::mapChanged, this, qOverload<>(&QWidget::update));
  connect(&model, &EditorModel::selectionChanged, this, qOverload<>(&QWidget::update));
  connect(&model, &EditorModel::issuesChanged, this, qOverload<>(&QWidget::update));
}

bool EditorLayer::eventFilter(QObject* watched, QEvent* event) {
  if (watched == &canvas_ && event->type() == QEvent::Resize)
    setGeometry(canvas_.rect());
  return QWidget::eventFilter(watched, event);
}

void EditorLayer::setTool(EditorTool tool) {
  if (tool == tool_)
    return;
  cancelDraft();
  edge_from_.clear();
  calibration_a_.reset();
  drag_ = Drag::kNone;
  tool_ = tool;  // a measurement stays on the map until Escape or the next one
  setCursor(tool == EditorTool::kSelect ? Qt::ArrowCursor : Qt::CrossCursor);
  update();
  emit toolChanged(tool);
}

std::optional<std::pair<Vec2, Vec2>> EditorLayer::measurement() const {
  return measure_;
}

Vec2 EditorLayer::toWorld(const QPointF& p) const {
  return canvas_.widgetToWorld(p);
}
QPointF EditorLayer::toWidget(const Vec2& p) const {
  return canvas_.worldToWidget(p);
}
double EditorLayer::pixelsToMetres(double px) const {
  return px / canvas_.pixelsPerMetre();
}

editing::SnapResult EditorLayer::snapped(const Vec2& world, const std::optional<Vec2>& anchor,
                                         const std::vector<ElementRef>& exclude) const {
  editing::SnapSettings s = model_.snapSettings();
  s.endpoint_radius_m = pixelsToMetres(kSnapRadius_px);
  std::vector<Vec2> targets = editing::snapTargets(model_.map(), exclude);
  targets.insert(targets.end(), draft_.begin(), draft_.end());
  return editing::snapPoint(world, s, targets, anchor);
}

void EditorLayer::addDraftPoint(const Vec2& world, bool snap) {
  const std::optional<Vec2> anchor =
      draft_.empty() ? std::nullopt : std::optional<Vec2>(draft_.back());
  const Vec2 p = snap ? snapped(world, anchor).point : world;
  if (!draft_.empty() && (p - draft_.back()).norm() < 1e-9)
    return;  // a repeated click adds nothing
  draft_.push_back(p);
  update();
}

void EditorLayer::finishDraft() {
  if (draft_.empty())
    return;
  std::vector<Vec2> points = std::move(draft_);
  draft_.clear();
  if (tool_ == EditorTool::kWall) {
    if (points.size() < 2) {
      emit message(tr("A wall needs at least two points"));
    } else {
      Wall wall;
      wall.points = std::move(points);
      // Ends placed on the same point close the outline.
      if (wall.points.size() > 3 && (wall.points.front() - wall.points.back()).norm() < 1e-9) {
        wall.points.pop_back();
        wall.closed = true;
      }
      model_.tryApply([&](const WorldMap& m) { return editing::addElement(m, wall); });
    }
  } else if (tool_ == EditorTool::kPolygon) {
    if (points.size() < 3) {
      emit message(tr("An obstacle needs at least three points"));
    } else {
      Obstacle obstacle;
      obstacle.polygon = std::move(points);
      model_.tryApply([&](const WorldMap& m) { return editing::addElement(m, obstacle); });
    }
  }
  update();
}

void EditorLayer::cancelDraft() {
  draft_.clear();
  update();
}

// --- Mouse ---------------------------------------------------------------------------------------

void EditorLayer::mousePressEvent(QMouseEvent* event) {
  const QPointF pos = event->position();
  const Vec2 world = toWorld(pos);
  const bool no_snap =
      event->modifiers().testFlag(Qt::ShiftModifier) && tool_ != EditorTool::kSelect;
  if (event->button() == Qt::RightButton &&
      (tool_ == EditorTool::kWall || tool_ == EditorTool::kPolygon) && !draft_.empty()) {
    finishDraft();
    event->accept();
    return;
  }
  if (event->button() != Qt::LeftButton) {
    event->ignore();  // middle button: the canvas pans
    return;
  }
  setFocus(Qt::MouseFocusReason);
  press_px_ = pos;
  press_world_ = world;
  drag_moved_ = false;
  switch (tool_) {
    case EditorTool::kSelect:
      pressSelect(world, pos, event->modifiers());
      break;
    case EditorTool::kWall:
    case EditorTool::kPolygon:
      // A click on the first point closes the outline.
      if (draft_.size() >= 3 &&
          (toWidget(draft_.front()) - pos).manhattanLength() <= 2.0 * kSnapRadius_px) {
        if (tool_ == EditorTool::kWall)
          draft_.push_back(draft_.front());
        finishDraft();
      } else {
        addDraftPoint(world, !no_snap);
      }
      break;
    case EditorTool::kStart:
      press_world_ =
          no_snap ? world : snapped(world, std::nullopt, {{ElementKind::kStart, 0}}).point;
      drag_world_ = press_world_;
      drag_ = Drag::kStartHeading;
      break;
    case EditorTool::kCorner:
    case EditorTool::kEdge: {
      PointFeature f;
      f.kind = tool_ == EditorTool::kCorner ? PointFeatureKind::kCorner : PointFeatureKind::kEdge;
      f.position = no_snap ? world : snapped(world, std::nullopt).point;
      model_.tryApply([&](const WorldMap& m) { return editing::addElement(m, f); });
      break;
    }
    case EditorTool::kMeasure: {
      const Vec2 p = no_snap ? world : snapped(world, std::nullopt).point;
      measure_ = std::make_pair(p, p);
      drag_ = Drag::kMeasure;
      break;
    }
    case EditorTool::kCeilingMarker:
      // Like the start pose: press at the centre, drag towards the heading.
      press_world_ = no_snap ? world : snapped(world, std::nullopt).point;
      drag_world_ = press_world_;
      drag_ = Drag::kStartHeading;
      break;
    case EditorTool::kCeilingLight:
      press_world_ = no_snap ? world : snapped(world, std::nullopt).point;
      drag_world_ = press_world_;
      drag_ = Drag::kLightTube;
      break;
    case EditorTool::kGraphNode:
      placeNode(world, !no_snap);
      break;
    case EditorTool::kGraphEdge:
      clickEdgeNode(world);
      break;
    case EditorTool::kCalibrate: {
      // Image points are clicked where the drawing shows them: no snapping.
      const std::optional<FloorPlan>& plan = model_.map().floor_plan;
      if (!plan) {
        emit message(tr("Open a floor plan first (Floor Plan…)"));
        break;
      }
      const Vec2 pixel = editing::worldToFloorPlan(*plan, world);
      if (!calibration_a_) {
        calibration_a_ = pixel;
        emit calibrationStarted(world.x(), world.y());
        emit message(tr("Calibration: now click the second point of the floor plan"));
      } else {
        const Vec2 a = *calibration_a_;
        calibration_a_.reset();
        emit calibrationRequested(QPointF(a.x(), a.y()), QPointF(pixel.x(), pixel.y()));
      }
      break;
    }
  }
  event->accept();
  update();
}

std::optional<std::size_t> EditorLayer::nodeNear(const Vec2& world) const {
  std::optional<std::size_t> best;
  double best_d = 2.0 * pixelsToMetres(kPickRadius_px);
  const auto& nodes = model_.map().graph.nodes;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const double d = (nodes[i].position - world).norm();
    if (d <= best_d) {
      best_d = d;
      best = i;
    }
  }
  return best;
}

void EditorLayer::placeNode(const Vec2& world, bool snap) {
  TopoNode node;
  node.position = snap ? snapped(world, std::nullopt).point : world;
  // On a ceiling marker the node sits at the marker's centre and is tied to it (002_…: the
  // nodes of the graph are the markers).
  const auto& markers = model_.map().markers;
  for (const CeilingMarker& m : markers) {
    const Vec2 d = world - m.position;
    const double c = std::cos(m.heading_rad), s = std::sin(m.heading_rad);
    const double reach = 0.5 * m.size_m + pixelsToMetres(kPickRadius_px);
    if (std::abs(c * d.x() + s * d.y()) <= reach && std::abs(-s * d.x() + c * d.y()) <= reach) {
      node.position = m.position;
      node.marker_id = m.id;
      break;
    }
  }
  if (model_.tryApply([&](const WorldMap& m) { return editing::addElement(m, node); }) &&
      !node.marker_id.empty())
    emit message(tr("Node tied to marker '%1'").arg(QString::fromStdString(node.marker_id)));
}

void EditorLayer::clickEdgeNode(const Vec2& world) {
  const std::optional<std::size_t> hit = nodeNear(world);
  if (!hit) {
    emit message(tr("Click a graph node to start or end the edge"));
    return;
  }
  const std::string id = model_.map().graph.nodes[*hit].id;
  if (edge_from_.empty() || edge_from_ == id || model_.map().graph.node(edge_from_) == nullptr) {
    edge_from_ = id;
    emit message(tr("Edge from node '%1': click the other node").arg(QString::fromStdString(id)));
    return;
  }
  TopoEdge edge;
  edge.from = edge_from_;
  edge.to = id;
  edge_from_.clear();
  model_.tryApply([&](const WorldMap& m) { return editing::addElement(m, edge); });
}

void EditorLayer::pressSelect(const Vec2& world, const QPointF& pos, Qt::KeyboardModifiers mods) {
  (void)pos;
  const std::optional<editing::Hit> hit =
      editing::hitTest(model_.map(), world, pixelsToMetres(kPickRadius_px));
  const bool additive = mods.testFlag(Qt::ShiftModifier) || mods.testFlag(Qt::ControlModifier);
  if (!hit) {
    if (!additive)
      model_.setSelection({});
    drag_ = Drag::kRubberBand;
    drag_world_ = world;
    return;
  }
  const bool selected = model_.isSelected(hit->ref);
  if (hit->vertex && selected && model_.selection().size() == 1) {
    drag_ = Drag::kVertex;
    vertex_ref_ = hit->ref;
    vertex_index_ = *hit->vertex;
    drag_world_ = editing::elementPoints(model_.map(),
                                         editing::elementAt(model_.map(), hit->ref))[*hit->vertex];
    return;
  }
  if (additive) {
    std::vector<ElementRef> sel = model_.selection();
    if (selected)
      std::erase(sel, hit->ref);
    else
      sel.push_back(hit->ref);
    model_.setSelection(std::move(sel));
    drag_ = Drag::kNone;
    return;
  }
  if (!selected)
    model_.setSelection({hit->ref});
  // Move by the grabbed element's nearest point so that point snaps (to grid or endpoints).
  const std::vector<Vec2> pts =
      editing::elementPoints(model_.map(), editing::elementAt(model_.map(), hit->ref));
  grab_point_ = pts.front();
  for (const Vec2& q : pts)
    if ((q - world).norm() < (grab_point_ - world).norm())
      grab_point_ = q;
  drag_world_ = grab_point_;
  drag_ = Drag::kMove;
}

void EditorLayer::mouseMoveEvent(QMouseEvent* event) {
  const QPointF pos = event->position();
  const Vec2 world = toWorld(pos);
  emit canvas_.cursorMoved(world.x(), world.y());
  const bool no_snap = event->modifiers().testFlag(Qt::ShiftModifier);
  if ((pos - press_px_).manhattanLength() > kDragSlop_px)
    drag_moved_ = true;
  switch (drag_) {
    case Drag::kNone: {
      const std::optional<Vec2> anchor =
          draft_.empty() ? std::nullopt : std::optional<Vec2>(draft_.back());
      const editing::SnapResult s =
          no_snap ? editing::SnapResult{world, SnapKind::kNone} : snapped(world, anchor);
      hover_ = s.point;
      hover_kind_ = s.kind;
      break;
    }
    case Drag::kMove:
      drag_world_ =
          no_snap ? Vec2(grab_point_ + (world - press_world_))
                  : snapped(grab_point_ + (world - press_world_), std::nullopt, model_.selection())
                        .point;
      break;
    case Drag::kVertex:
      drag_world_ = no_snap ? world : snapped(world, std::nullopt, {vertex_ref_}).point;
      break;
    case Drag::kRubberBand:
    case Drag::kStartHeading:
      drag_world_ = world;
      break;
    case Drag::kLightTube:
      drag_world_ = no_snap ? world : snapped(world, press_world_).point;
      break;
    case Drag::kMeasure:
      if (measure_)
        measure_->second = no_snap ? world : snapped(world, measure_->first).point;
      break;
  }
  update();
}

void EditorLayer::mouseReleaseEvent(QMouseEvent* event) {
  if (event->button() != Qt::LeftButton) {
    event->ignore();
    return;
  }
  const Drag drag = drag_;
  drag_ = Drag::kNone;
  const Vec2 world = toWorld(event->position());
  switch (drag) {
    case Drag::kNone:
      break;
    case Drag::kMove:
      if (drag_moved_) {
        const Vec2 delta = drag_world_ - grab_point_;
        const std::vector<ElementRef> sel = model_.selection();
        if (delta.norm() > 0.0)
          model_.tryApply([&](const WorldMap& m) { return editing::moveElements(m, sel, delta); });
      }
      break;
    case Drag::kVertex:
      if (drag_moved_) {
        model_.tryApply([&](const WorldMap& m) {
          return editing::moveVertex(m, vertex_ref_, vertex_index_, drag_world_);
        });
      }
      break;
    case Drag::kRubberBand: {
      if (!drag_moved_)
        break;
      Box2 box;
      box.extend(press_world_);
      box.extend(world);
      std::vector<ElementRef> sel = editing::elementsInBox(model_.map(), box);
      if (event->modifiers().testFlag(Qt::ShiftModifier))
        sel.insert(sel.end(), model_.selection().begin(), model_.selection().end());
      model_.setSelection(std::move(sel));
      break;
    }
    case Drag::kStartHeading: {
      const bool marker = tool_ == EditorTool::kCeilingMarker;
      double theta = marker ? 0.0 : model_.map().start.theta;
      const Vec2 d = world - press_world_;
      if (drag_moved_ && d.norm() > pixelsToMetres(kDragSlop_px)) {
        theta = std::atan2(d.y(), d.x());
        const double step = model_.snapSettings().angle_step_rad;
        if (step > 0.0 && !event->modifiers().testFlag(Qt::ShiftModifier))
          theta = editing::roundToStep(theta, step);
      }
      if (marker) {
        CeilingMarker m;
        m.position = press_world_;
        m.heading_rad = theta;
        model_.tryApply([&](const WorldMap& map) { return editing::addElement(map, m); });
        break;
      }
      const Pose2 start{press_world_.x(), press_world_.y(), theta};
      model_.tryApply([&](const WorldMap& m) { return editing::setStart(m, start); });
      break;
    }
    case Drag::kLightTube: {
      if (!drag_moved_ || (drag_world_ - press_world_).norm() < 1e-6) {
        emit message(tr("Drag from one end of the light tube to the other"));
        break;
      }
      CeilingLight light;
      light.tube = {press_world_, drag_world_};
      model_.tryApply([&](const WorldMap& m) { return editing::addElement(m, light); });
      break;
    }
    case Drag::kMeasure:
      if (measure_) {
        const Vec2 d = measure_->second - measure_->first;
        const double heading = d.norm() > 0.0 ? std::atan2(d.y(), d.x()) : 0.0;
        emit measured(d.norm(), heading);
        emit message(tr("Distance %1 m, heading %2°, Δx %3 m, Δy %4 m")
                         .arg(d.norm(), 0, 'f', 3)
                         .arg(radToDeg(heading), 0, 'f', 1)
                         .arg(d.x(), 0, 'f', 3)
                         .arg(d.y(), 0, 'f', 3));
      }
      break;
  }
  event->accept();
  update();
}

void EditorLayer::mouseDoubleClickEvent(QMouseEvent* event) {
  if (event->button() == Qt::LeftButton &&
      (tool_ == EditorTool::kWall || tool_ == EditorTool::kPolygon)) {
    finishDraft();  // the first click of the double click placed the last point
    event->accept();
    return;
  }
  if (event->button() == Qt::LeftButton) {
    event->accept();  // not the canvas's zoom-to-fit while editing
    return;
  }
  event->ignore();
}

void EditorLayer::wheelEvent(QWheelEvent* event) {
  event->ignore();  // the canvas zooms
}

void EditorLayer::keyPressEvent(QKeyEvent* event) {
  const bool drawing = !draft_.empty();
  switch (event->key()) {
    case Qt::Key_Escape:
      if (calibration_a_)
        calibration_a_.reset();
      else if (!edge_from_.empty())
        edge_from_.clear();
      else if (drawing)
        cancelDraft();
      else if (drag_ != Drag::kNone)
        drag_ = Drag::kNone;
      else if (measure_)
        measure_.reset();
      else
        model_.setSelection({});
      update();
      return;
    case Qt::Key_Return:
    case Qt::Key_Enter:
      if (drawing) {
        finishDraft();
        return;
      }
      break;
    case Qt::Key_Backspace:
      if (drawing) {
        draft_.pop_back();
        update();
        return;
      }
      model_.deleteSelection();
      return;
    case Qt::Key_Delete:
      model_.deleteSelection();
      return;
    default:
      break;
  }
  event->ignore();  // the canvas's keys (fit, zoom) still work
}

// --- Painting ------------------------------------------------------------------------------------

void EditorLayer::paintElementOutline(QPainter& p, const ElementRef& ref) const {
  if (!editing::isValidRef(model_.map(), ref))
    return;
  const editing::Element e = editing::elementAt(model_.map(), ref);
  const std::vector<Vec2> pts = editing::elementPoints(model_.map(), e);
  QPolygonF poly;
  for (const Vec2& q : pts)
    poly << toWidget(q);
  p.setBrush(Qt::NoBrush);
  p.setPen(QPen(kSelection, 3.0, Qt::SolidLine, Qt::RoundCap, Qt::RoundJoin));
  // Markers and lights: their square / tube, plus the heading tick or the end handles.
  if (const auto* m = std::get_if<CeilingMarker>(&e)) {
    QPolygonF square;
    for (const Vec2& q : rectangle(m->position, m->heading_rad, m->size_m, m->size_m))
      square << toWidget(q);
    p.drawPolygon(square);
    const Vec2 tip =
        m->position + 0.5 * m->size_m * Vec2(std::cos(m->heading_rad), std::sin(m->heading_rad));
    p.drawLine(toWidget(m->position), toWidget(tip));
    return;
  }
  if (const auto* l = std::get_if<CeilingLight>(&e)) {
    const Vec2 d = l->tube.b - l->tube.a;
    QPolygonF tube;
    for (const Vec2& q :
         rectangle((l->tube.a + l->tube.b) / 2.0, std::atan2(d.y(), d.x()), d.norm(), l->width_m))
      tube << toWidget(q);
    p.drawPolygon(tube);
  }
  if (pts.size() == 1) {
    p.drawEllipse(poly.front(), 9.0, 9.0);
    return;
  }
  if (isClosed(e))
    p.drawPolygon(poly);
  else if (!std::holds_alternative<CeilingLight>(e))
    p.drawPolyline(poly);
  if (std::holds_alternative<TopoEdge>(e))
    return;  // the nodes are the handles of their own
  p.setBrush(Qt::white);
  p.setPen(QPen(kSelection, 1.5));
  for (const QPointF& q : poly)
    p.drawRect(QRectF(q - QPointF(3.5, 3.5), QSizeF(7.0, 7.0)));
}

void EditorLayer::paintIssues(QPainter& p) const {
  QFont font = p.font();
  font.setBold(true);
  p.setFont(font);
  for (const editing::MapIssue& issue : model_.issues()) {
    const QColor colour = issue.severity == Severity::kError ? kIssueError : kIssueWarning;
    const QPointF c = toWidget(issue.position);
    p.setPen(QPen(colour.darker(130), 1.5));
    QColor fill = colour;
    fill.setAlpha(220);
    p.setBrush(fill);
    p.drawEllipse(c + QPointF(10, -10), 8.0, 8.0);
    p.setPen(Qt::white);
    p.drawText(QRectF(c + QPointF(2, -18), QSizeF(16, 16)), Qt::AlignCenter, QStringLiteral("!"));
    p.setPen(QPen(colour, 2.0));
    p.setBrush(Qt::NoBrush);
    p.drawEllipse(c, 5.0, 5.0);
  }
}

void EditorLayer::paintEvent(QPaintEvent*) {
  QPainter p(this);
  p.setRenderHint(QPainter::Antialiasing);

  // Selection; during a move, the outlines follow the cursor.
  const bool moving = drag_ == Drag::kMove && drag_moved_;
  if (moving) {
    p.save();
    const QPointF shift = toWidget(drag_world_) - toWidget(grab_point_);
    p.translate(shift);
  }
  for (const ElementRef& ref : model_.selection())
    paintElementOutline(p, ref);
  if (moving)
    p.restore();

  if (drag_ == Drag::kVertex && drag_moved_) {
    std::vector<Vec2> pts =
        editing::elementPoints(model_.map(), editing::elementAt(model_.map(), vertex_ref_));
    const std::size_t n = pts.size();
    p.setPen(QPen(kSelection, 2.0, Qt::DashLine));
    const QPointF v = toWidget(drag_world_);
    const bool closed = isClosed(editing::elementAt(model_.map(), vertex_ref_));
    if (vertex_index_ > 0 || closed)
      p.drawLine(toWidget(pts[(vertex_index_ + n - 1) % n]), v);
    if (vertex_index_ + 1 < n || closed)
      p.drawLine(v, toWidget(pts[(vertex_index_ + 1) % n]));
    p.drawRect(QRectF(v - QPointF(4, 4), QSizeF(8, 8)));
  }

  // Outline being drawn, with the rubber segment to the cursor.
  if (!draft_.empty()) {
    QPolygonF poly;
    for (const Vec2& q : draft_)
      poly << toWidget(q);
    p.setPen(QPen(kDraft, 2.5, Qt::SolidLine, Qt::RoundCap, Qt::RoundJoin));
    p.setBrush(Qt::NoBrush);
    p.drawPolyline(poly);
    if (hover_) {
      p.setPen(QPen(kDraft, 1.5, Qt::DashLine));
      p.drawLine(poly.back(), toWidget(*hover_));
      if (tool_ == EditorTool::kPolygon && draft_.size() >= 2)
        p.drawLine(toWidget(*hover_), poly.front());
      const Vec2 d = *hover_ - draft_.back();
      p.setPen(kDraft.darker(150));
      p.drawText(toWidget(*hover_) + QPointF(12, 16),
                 QStringLiteral("%1 m  %2°")
                     .arg(d.norm(), 0, 'f', 2)
                     .arg(radToDeg(std::atan2(d.y(), d.x())), 0, 'f', 0));
    }
    p.setBrush(Qt::white);
    p.setPen(QPen(kDraft, 1.5));
    for (const QPointF& q : poly)
      p.drawEllipse(q, 3.5, 3.5);
    if (draft_.size() >= 3) {  // the first point closes the outline
      p.setBrush(Qt::NoBrush);
      p.drawEllipse(poly.front(), 2.0 * kSnapRadius_px / 1.5, 2.0 * kSnapRadius_px / 1.5);
    }
  }

  // Snap indicator under the cursor for the placing tools.
  if (hover_ && tool_ != EditorTool::kSelect && drag_ == Drag::kNone) {
    const QPointF c = toWidget(*hover_);
    p.setBrush(Qt::NoBrush);
    switch (hover_kind_) {
      case SnapKind::kEndpoint:
        p.setPen(QPen(QColor(0, 160, 60), 2.0));
        p.drawRect(QRectF(c - QPointF(6, 6), QSizeF(12, 12)));
        break;
      case SnapKind::kAngle:
        p.setPen(QPen(QColor(0, 160, 60), 2.0));
        p.drawPolygon(QPolygonF(
            {c + QPointF(0, -7), c + QPointF(7, 0), c + QPointF(0, 7), c + QPointF(-7, 0)}));
        break;
      case SnapKind::kGrid:
        p.setPen(QPen(QColor(60, 60, 60), 1.5));
        p.drawLine(c - QPointF(6, 0), c + QPointF(6, 0));
        p.drawLine(c - QPointF(0, 6), c + QPointF(0, 6));
        break;
      case SnapKind::kNone:
        p.setPen(QPen(QColor(60, 60, 60), 1.0));
        p.drawEllipse(c, 3.0, 3.0);
        break;
    }
  }

  if (drag_ == Drag::kRubberBand && drag_moved_) {
    p.setPen(QPen(kSelection, 1.0, Qt::DashLine));
    QColor fill = kSelection;
    fill.setAlpha(30);
    p.setBrush(fill);
    p.drawRect(QRectF(toWidget(press_world_), toWidget(drag_world_)).normalized());
  }

  if (drag_ == Drag::kLightTube) {
    p.setPen(QPen(kDraft, 6.0, Qt::SolidLine, Qt::RoundCap));
    p.drawLine(toWidget(press_world_), toWidget(drag_world_));
    const Vec2 d = drag_world_ - press_world_;
    p.setPen(kDraft.darker(150));
    p.drawText(toWidget(drag_world_) + QPointF(12, 16),
               QStringLiteral("%1 m  %2°")
                   .arg(d.norm(), 0, 'f', 2)
                   .arg(radToDeg(std::atan2(d.y(), d.x())), 0, 'f', 0));
  }

  if (tool_ == EditorTool::kGraphEdge && !edge_from_.empty()) {
    if (const TopoNode* from = model_.map().graph.node(edge_from_)) {
      p.setPen(QPen(kDraft, 2.5));
      p.setBrush(Qt::NoBrush);
      p.drawEllipse(toWidget(from->position), 9.0, 9.0);
      if (hover_) {
        p.setPen(QPen(kDraft, 2.0, Qt::DashLine));
        p.drawLine(toWidget(from->position), toWidget(*hover_));
      }
    }
  }

  if (calibration_a_ && model_.map().floor_plan) {
    const QPointF a =
        toWidget(editing::floorPlanToWorld(*model_.map().floor_plan, *calibration_a_));
    p.setPen(QPen(kMeasure, 2.0));
    p.drawLine(a - QPointF(8, 0), a + QPointF(8, 0));
    p.drawLine(a - QPointF(0, 8), a + QPointF(0, 8));
    p.drawText(a + QPointF(6, -6), QStringLiteral("A"));
    if (hover_) {
      p.setPen(QPen(kMeasure, 1.5, Qt::DashLine));
      p.drawLine(a, toWidget(*hover_));
    }
  }

  if (drag_ == Drag::kStartHeading) {
    const QPointF a = toWidget(press_world_);
    p.setPen(QPen(kDraft, 2.5));
    p.setBrush(Qt::NoBrush);
    p.drawEllipse(a, 8.0, 8.0);
    if (drag_moved_)
      p.drawLine(a, toWidget(drag_world_));
  }

  if (measure_) {
    const QPointF a = toWidget(measure_->first), b = toWidget(measure_->second);
    p.setPen(QPen(kMeasure, 2.0, Qt::DashLine));
    p.drawLine(a, b);
    p.setBrush(kMeasure);
    p.drawEllipse(a, 3.0, 3.0);
    p.drawEllipse(b, 3.0, 3.0);
    const Vec2 d = measure_->second - measure_->first;
    const QString label = QStringLiteral("%1 m  %2°")
                              .arg(d.norm(), 0, 'f', 3)
                              .arg(radToDeg(std::atan2(d.y(), d.x())), 0, 'f', 1);
    const QPointF at = (a + b) / 2.0 + QPointF(8, -8);
    const QRectF box =
        QFontMetricsF(font()).boundingRect(label).translated(at).adjusted(-4, -2, 4, 2);
    p.setPen(Qt::NoPen);
    p.setBrush(QColor(255, 255, 255, 220));
    p.drawRoundedRect(box, 3, 3);
    p.setPen(kMeasure);
    p.drawText(at, label);
  }

  paintIssues(p);
}

}  // namespace irgs::widgets
