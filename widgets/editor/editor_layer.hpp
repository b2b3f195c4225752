#pragma once
// The editor's tool layer: a transparent widget laid over the MapCanvas that turns mouse and
// keys into core edits on an EditorModel and draws the selection, the tool previews, the snap
// indicator, the measure line and the validation markers.
//
// Tools: select (click, shift-click to add, rubber band; drag to move the selection or a
// vertex of the selected wall/obstacle), draw wall (click points; double-click, Enter or a
// right click finishes; clicking the first point closes the outline), draw polygon obstacle
// (likewise, at least three points), place start pose (press at the position, drag for the
// heading), corner/edge feature (click), ceiling marker (press at the centre, drag for the
// heading), ceiling light (drag from one end of the tube to the other), graph node (click; on a
// marker it lands on the marker's centre, tied to it), graph edge (click one node, then another),
// floor-plan calibration (click two points of the image: the panel applies the distance and
// the first point's position), measure (drag). Points snap per the model's snap
// settings; Shift while drawing disables snapping. Escape cancels, Backspace removes the last
// drawn point, Delete deletes the selection. The wheel and the middle button pass through to
// the canvas (zoom and pan).

#include <QPointF>
#include <QWidget>
#include <optional>
#include <string>
#include <vector>

#include "core/editing/map_edit.hpp"
#include "core/editing/snapping.hpp"

namespace irgs::widgets {

class EditorModel;
class MapCanvas;

enum class EditorTool {
  kSelect,
  kWall,
  kPolygon,
  kStart,
  kCorner,
  kEdge,
  kCeilingMarker,
  kCeilingLight,
  kGraphNode,
  kGraphEdge,
  kCalibrate,
  kMeasure,
};

class EditorLayer : public QWidget {
  Q_OBJECT

 public:
  // Snap and pick radii in screen pixels (converted to metres at the current zoom).
  static constexpr double kSnapRadius_px = 10.0;
  static constexpr double kPickRadius_px = 7.0;
  static constexpr double kDragSlop_px = 3.0;

  // Parented to the canvas and kept covering it; both must outlive the layer.
  EditorLayer(MapCanvas& canvas, EditorModel& model);

  void setTool(EditorTool tool);
  EditorTool tool() const { return tool_; }
  // Points of the outline being drawn (wall/polygon tools).
  const std::vector<irgs::Vec2>& draftPoints() const { return draft_; }
  // The node an edge being drawn starts from (graph edge tool), or "".
  const std::string& edgeStart() const { return edge_from_; }
  // The last measurement: from, to (world metres).
  std::optional<std::pair<irgs::Vec2, irgs::Vec2>> measurement() const;
  // Finishes / abandons the outline being drawn.
  void finishDraft();
  void cancelDraft();

  // Where a point placed at `world` lands with the current snap settings (anchor: the previous
  // point of the outline being drawn).
  irgs::editing::SnapResult snapped(
      const irgs::Vec2& world, const std::optional<irgs::Vec2>& anchor,
      const std::vector<irgs::editing::ElementRef>& exclude = {}) const;

 signals:
  void toolChanged(irgs::widgets::EditorTool tool);
  void measured(double distance_m, double heading_rad);
  void message(const QString& text);  // hints and results for the status bar
  // Calibrate tool: the first image point was clicked (where it lies now, world metres); then
  // both points, as floor-plan image pixels.
  void calibrationStarted(double x_m, double y_m);
  void calibrationRequested(QPointF pixel_a, QPointF pixel_b);

 protected:
  bool eventFilter(QObject* watched, QEvent* event) override;
  void paintEvent(QPaintEvent* event) override;
  void mousePressEvent(QMouseEvent* event) override;
  void mouseMoveEvent(QMouseEvent* event) override;
  void mouseReleaseEvent(QMouseEvent* event) override;
  void mouseDoubleClickEvent(QMouseEvent* event) override;
  void wheelEvent(QWheelEvent* event) override;
  void keyPressEvent(QKeyEvent* event) override;

 private:
  enum class Drag { kNone, kMove, kVertex, kRubberBand, kStartHeading, kMeasure, kLightTube };

  irgs::Vec2 toWorld(const QPointF& p) const;
  QPointF toWidget(const irgs::Vec2& p) const;
  double pixelsToMetres(double px) const;
  void addDraftPoint(const irgs::Vec2& world, bool snap);
  void pressSelect(const irgs::Vec2& world, const QPointF& pos, Qt::KeyboardModifiers mods);
  void releaseSelect(const irgs::Vec2& world, Qt::KeyboardModifiers mods);
  void paintElementOutline(QPainter& p, const irgs::editing::ElementRef& ref) const;
  void paintIssues(QPainter& p) const;
  void placeNode(const irgs::Vec2& world, bool snap);
  void clickEdgeNode(const irgs::Vec2& world);
  // The graph node within the pick radius of `world`, or nothing.
  std::optional<std::size_t> nodeNear(const irgs::Vec2& world) const;

  MapCanvas& canvas_;
  EditorModel& model_;
  EditorTool tool_ = EditorTool::kSelect;

  std::vector<irgs::Vec2> draft_;    // outline being drawn
  std::optional<irgs::Vec2> hover_;  // snapped cursor position
  irgs::editing::SnapKind hover_kind_ = irgs::editing::SnapKind::kNone;

  Drag drag_ = Drag::kNone;
  QPointF press_px_;
  irgs::Vec2 press_world_ = irgs::Vec2::Zero();
  irgs::Vec2 grab_point_ = irgs::Vec2::Zero();  // the point of the selection that was grabbed
  irgs::Vec2 drag_world_ = irgs::Vec2::Zero();  // current (snapped) drag position
  bool drag_moved_ = false;
  irgs::editing::ElementRef vertex_ref_;
  std::size_t vertex_index_ = 0;
  std::optional<std::pair<irgs::Vec2, irgs::Vec2>> measure_;
  std::string edge_from_;                    // graph edge tool: the first node clicked
  std::optional<irgs::Vec2> calibration_a_;  // calibrate tool: the first image pixel
};

}  // namespace irgs::widgets
