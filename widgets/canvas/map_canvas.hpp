#pragma once
// The map view of the ground station: a custom-painted, pannable and zoomable top view of the
// world map, the live occupancy grid and the robot with its sensors.
//
// View model: a uniform scale (pixels per metre) and the world point at the widget centre.
// World +x points right and +y points up on screen. Static layers (floor, metric grid, raster,
// walls, obstacles, features, ceiling, graph) are cached in pixmaps that are re-rendered only
// when the scale changes or the view leaves the cached margin; the occupancy grid is a cached
// image updated from the grid's dirty rectangle; the robot, sonar cones and trail are painted
// each frame.
//
// Interaction: drag with the left or middle button to pan, wheel to zoom about the cursor,
// double-click or Home to fit, +/- to zoom about the centre, F to toggle following the robot.
// Planning modes (setInteraction): "pick goal" turns a left click (press and release within a
// few pixels) into worldClicked(); "select region" turns a left drag into regionSelected();
// the middle button still pans and Escape returns to navigation.

#include <QImage>
#include <QPainterPath>
#include <QPixmap>
#include <QPolygonF>
#include <QWidget>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <optional>
#include <unordered_map>
#include <vector>

#include "core/geometry/types.hpp"
#include "core/mapping/occupancy_grid.hpp"
#include "core/robot/robot_profile.hpp"
#include "core/robot/telemetry.hpp"
#include "core/world/world_map.hpp"
#include "widgets/canvas/estimator_overlay.hpp"
#include "widgets/canvas/grid_tiles.hpp"
#include "widgets/canvas/map_layers_painter.hpp"
#include "widgets/canvas/map_view.hpp"
#include "widgets/canvas/navigation_overlay.hpp"
#include "widgets/canvas/path_overlay.hpp"
#include "widgets/canvas/robot_painter.hpp"
#include "widgets/canvas/static_layer_cache.hpp"
#include "widgets/canvas/trail_cache.hpp"

namespace irgs::widgets {

class MapCanvas : public QWidget {
  Q_OBJECT

 public:
  enum class Layer { kRaster, kGrid, kWalls, kFeatures, kCeiling, kGraph, kSonar, kTrail, kTruth };
  enum class Interaction { kNavigate, kPickGoal, kSelectRegion };
  // A press and release closer than this is a click, not a drag, px.
  static constexpr double kClickSlop_px = 4.0;

  // Zoom limits, pixels per metre.
  static constexpr double kMinPixelsPerMetre = 0.2;
  static constexpr double kMaxPixelsPerMetre = 5000.0;
  // Trail bounds: at most this many points, a new point only after this distance.
  static constexpr std::size_t kMaxTrailPoints = 20000;
  static constexpr double kTrailStep_m = 0.02;
  // A sonar cone is no longer drawn when its reading is older than this (telemetry time).
  static constexpr double kSonarStale_s = 1.0;

  explicit MapCanvas(QWidget* parent = nullptr);
  ~MapCanvas() override;

  // Copies the map; the static layers are redrawn.
  void setWorldMap(const irgs::WorldMap& map);
  void setRobotProfile(const irgs::RobotProfile& profile);

  // The live occupancy grid (non-owning, may be nullptr; must outlive its use here).
  // With a mutable grid, gridUpdated() pulls grid->takeDirtyRect() and redraws only that part.
  // With a const grid the canvas cannot take the dirty rect: gridUpdated() then redraws the whole
  // observed area unless the caller passes the rect it took itself to gridUpdated(rect).
  void setGrid(irgs::OccupancyGrid* grid);
  void setGrid(const irgs::OccupancyGrid* grid);
  void setGrid(std::nullptr_t);
  void gridUpdated();
  void gridUpdated(const irgs::OccupancyGrid::CellRect& dirty_cells);

  // Odometry pose (the robot as drawn), truth ghost when s.true_pose is set, the latest sonar
  // reading per sensor, bumpers; appends the odometry position to the trail. Samples with
  // non-finite poses are ignored.
  void setRobotState(const irgs::TelemetrySample& s);
  void clearTrail();
  std::size_t trailSize() const { return trail_.size(); }

  // Fits map bounds, grid bounds and the robot into the view. Until the user pans or zooms,
  // the view keeps fitting when the widget is resized.
  void zoomToFit();
  void setFollowRobot(bool follow);
  bool followRobot() const { return follow_robot_; }
  void setLayerVisible(Layer layer, bool visible);
  bool layerVisible(Layer layer) const;

  double pixelsPerMetre() const { return scale_; }
  irgs::Vec2 viewCentre() const { return centre_; }
  // Sets the view directly (clamped to the zoom limits).
  void setView(const irgs::Vec2& centre, double pixels_per_metre);
  // Zooms by `factor` keeping the world point under `anchor` (widget coordinates) fixed.
  void zoomAt(const QPointF& anchor, double factor);

  QPointF worldToWidget(const irgs::Vec2& p) const;
  irgs::Vec2 widgetToWorld(const QPointF& p) const;

  // Planning overlay (paths, goal, region, position indices), drawn under the robot.
  void setPlanningOverlay(PlanningOverlay overlay);
  const PlanningOverlay& planningOverlay() const { return overlay_; }
  void setInteraction(Interaction interaction);
  Interaction interaction() const { return interaction_; }

  // Localization overlay (estimator poses with ellipses, matched features), drawn over the robot.
  void setEstimatorOverlay(EstimatorOverlay overlay);
  const EstimatorOverlay& estimatorOverlay() const { return estimator_overlay_; }
  // Landmark-navigation overlay (route, state, avoidance vectors, moving obstacles).
  void setNavigationOverlay(NavigationOverlay overlay);
  const NavigationOverlay& navigationOverlay() const { return navigation_overlay_; }

  QSize sizeHint() const override { return {800, 600}; }
  QSize minimumSizeHint() const override { return {200, 150}; }

 signals:
  void cursorMoved(double x_m, double y_m);  // world coordinates under the mouse
  void viewChanged();
  void followRobotChanged(bool follow);  // also emitted when a drag ends following
  // Pick-goal mode: a left click at this world point.
  void worldClicked(double x_m, double y_m);
  // Select-region mode: the dragged rectangle, world metres (x0 <= x1, y0 <= y1).
  void regionSelected(double x0_m, double y0_m, double x1_m, double y1_m);
  void interactionChanged(irgs::widgets::MapCanvas::Interaction interaction);

 protected:
  void paintEvent(QPaintEvent* event) override;
  void resizeEvent(QResizeEvent* event) override;
  void mousePressEvent(QMouseEvent* event) override;
  void mouseMoveEvent(QMouseEvent* event) override;
  void mouseReleaseEvent(QMouseEvent* event) override;
  void mouseDoubleClickEvent(QMouseEvent* event) override;
  void wheelEvent(QWheelEvent* event) override;
  void keyPressEvent(QKeyEvent* event) override;

 private:
  MapView view() const;  // the current view as a value
  StaticLayerVisibility staticLayers() const;
  void invalidateCache();
  void viewWasChanged();
  void stopAutoFit();
  void redrawWholeGrid();
  void blitGridCells(irgs::OccupancyGrid::CellRect cells);
  irgs::Box2 contentBounds() const;

  // Static layers (map copy and prepared geometry) and their cached pictures.
  MapLayersPainter map_layers_;
  StaticLayerCache layer_cache_;
  TrailCache trail_cache_;

  // Robot profile and body outline.
  RobotPainter robot_;

  // Occupancy grid and its tiled picture.
  const irgs::OccupancyGrid* grid_ = nullptr;
  irgs::OccupancyGrid* mutable_grid_ = nullptr;
  GridTiles grid_tiles_;

  // Robot state.
  std::optional<irgs::Pose2> pose_;
  std::optional<irgs::Pose2> true_pose_;
  std::vector<std::optional<SonarState>> sonar_;  // latest per sensor
  double last_time_s_ = 0.0;
  std::uint32_t bumpers_ = 0;
  std::deque<irgs::Vec2> trail_;
  std::uint64_t trail_pushed_ = 0;  // points ever appended; trail_ holds the last trail_.size()

  // View.
  double scale_ = 50.0;
  irgs::Vec2 centre_ = irgs::Vec2::Zero();
  bool follow_robot_ = false;
  bool auto_fit_ = true;
  unsigned layers_ = ~0u;  // bit per Layer

  // Mouse drag.
  bool dragging_ = false;
  QPointF last_mouse_;

  // Planning overlay and modes.
  PlanningOverlay overlay_;
  EstimatorOverlay estimator_overlay_;
  NavigationOverlay navigation_overlay_;
  Interaction interaction_ = Interaction::kNavigate;
  QPointF press_pos_;                      // where the left button went down (pick goal)
  std::optional<irgs::Vec2> region_from_;  // select region: drag start and current corner
  irgs::Vec2 region_to_ = irgs::Vec2::Zero();
};

}  // namespace irgs::widgets
