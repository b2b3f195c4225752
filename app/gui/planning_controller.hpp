#pragma once
// The planning modes of the window, wired between the session, the map canvas and the planning
// panel: click-to-goal (preview the raw A* path beside the amended one, then drive it with
// TravelMission on the robot's segments primitive), coverage of a dragged region (preview, drive,
// live swept %), and map building (MapBuildingMission: start, pause, abort, phase/progress, indices
// on the canvas, save the built grid as a ROS map). Planning runs on the GUI thread inside a
// wall-time budget (PlanningSettings::budget_s; A* returns its best partial path when it runs out),
// so the window never waits longer than that for a preview.

#include <QObject>
#include <QString>
#include <memory>
#include <optional>

#include "app/gui/planning_tasks.hpp"
#include "core/mapping/occupancy_grid.hpp"
#include "core/robot/telemetry.hpp"

namespace irgs {
class MapBuildingMission;
class TravelMission;
struct TravelMissionConfig;
}  // namespace irgs

namespace irgs::widgets {
class MapCanvas;
class PlanningPanel;
enum class PlanSource;
}  // namespace irgs::widgets

namespace irgs::gui {

class BehaviourController;
class SessionController;

class PlanningController : public QObject {
  Q_OBJECT

 public:
  // All three must outlive the controller.
  PlanningController(SessionController& session, widgets::MapCanvas& canvas,
                     widgets::PlanningPanel& panel, QObject* parent = nullptr);
  ~PlanningController() override;

  // Plans from the robot's pose to `goal` on the panel's source and shows the preview. Returns
  // whether a drivable path was found.
  bool planGoal(const Vec2& goal);
  // Re-plans to the last goal from the robot's current pose and drives the amended path.
  bool driveGoal();
  // Plans coverage of `region` (world rectangle) and shows it.
  bool planRegion(const Box2& region);
  bool driveCoverage();
  bool startMapBuilding();
  void setMapBuildingPaused(bool paused);
  // Stops the task this controller runs (its Stop and Abort buttons); STOP stops any activity.
  void stopAll(const QString& reason);
  // Writes the built grid as ROS PGM + YAML; returns an error message on failure.
  std::optional<QString> saveBuiltMap(const QString& yaml_path);

  const std::optional<GoalPreview>& goalPreview() const { return goal_preview_; }
  const std::optional<CoveragePreview>& coveragePreview() const { return coverage_preview_; }
  // Live coverage of the region, 0..1, once a coverage run started.
  std::optional<double> coverage() const;
  BehaviourController& behaviours() { return *behaviours_; }
  const MapBuildingMission* mapBuilding() const;
  const std::optional<OccupancyGrid>& builtGrid() const { return built_grid_; }
  const PlanningSettings& settings() const { return settings_; }
  // Replaces the settings (the parameters panel); the next plan uses them. The travel speeds
  // (time_model) stay the controller's own.
  void setSettings(const PlanningSettings& settings);

 signals:
  void goalPreviewChanged();
  void coveragePreviewChanged();

 private:
  enum class Running { kNone, kGoal, kCoverage, kMapBuilding };

  void connectAll();
  std::optional<PlanningGrids> currentGrids();
  std::optional<Pose2> robotPose() const;
  void showGoalPreview();
  void showCoveragePreview();
  void refreshOverlay();
  void refreshLive();
  void onBehaviourFinished(bool failed, const QString& message);
  void onSample(const TelemetrySample& sample);
  void setRunning(Running running);
  // Asks the session's runner to start the task's behaviour (one of the two); false, with the
  // last run kept, when it refused.
  bool startBehaviour(Running running, std::shared_ptr<TravelMission> travel,
                      std::shared_ptr<MapBuildingMission> building, const QString& label);
  // Goal travel and coverage on the robot's segments primitive: the planning settings' quantum.
  TravelMissionConfig travelConfig(double stop_distance_m) const;
  void saveBuiltMapInteractively();
  void keepBuiltGrid();

  SessionController& session_;
  widgets::MapCanvas& canvas_;
  widgets::PlanningPanel& panel_;
  BehaviourController* behaviours_ = nullptr;
  // The last behaviour this controller started, by kind (shared with the runner while it runs).
  std::shared_ptr<TravelMission> travel_;
  std::shared_ptr<MapBuildingMission> building_;
  PlanningSettings settings_;

  Running running_ = Running::kNone;
  std::optional<Vec2> goal_;
  std::optional<GoalPreview> goal_preview_;
  std::optional<Box2> region_;
  std::optional<CoveragePreview> coverage_preview_;
  std::optional<CoverageSweep> sweep_;
  std::vector<Vec2> driven_path_;  // polyline being driven (for the reached turning points)
  std::size_t reached_ = 0;
  std::optional<OccupancyGrid> built_grid_;
  std::vector<Vec2> built_indices_;  // position indices of the last map-building run
  std::size_t shown_indices_ = 0;

  // The loaded map's planning grids, rebuilt when the world changes.
  std::optional<PlanningGrids> world_grids_;
};

}  // namespace irgs::gui
