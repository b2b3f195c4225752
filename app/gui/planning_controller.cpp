#include "app/gui/planning_controller.hpp"

#include <QElapsedTimer>
#include <QFileDialog>
#include <QFileInfo>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "app/gui/behaviour_controller.hpp"
#include "app/gui/session_controller.hpp"
#include "core/mapping/grid_export.hpp"
#include "core/mission/map_building_mission.hpp"
#include "core/mission/travel_mission.hpp"
#include "core/motion/motion_settings.hpp"
#include "widgets/canvas/map_canvas.hpp"
#include "widgets/planning/planning_panel.hpp"

namespace irgs::gui {
namespace {

// The turning points of a travel plan: where it starts, then every segment's end.
std::vector<Vec2> turningPoints(const TravelPlan& plan) {
  std::vector<Vec2> points;
  if (plan.segments.empty())
    return points;
  points.push_back(plan.segments.front().from);
  for (const TravelSegment& s : plan.segments)
    points.push_back(s.to);
  return points;
}

}  // namespace

namespace {

using widgets::MapCanvas;
using widgets::PlanningPanel;
using widgets::PlanSource;

// Forward-sonar safety stop while driving to a goal, m from the body origin.
constexpr double kGoalStopDistance_m = 0.25;

QString point(const Vec2& p) {
  return QStringLiteral("(%1, %2)").arg(p.x(), 0, 'f', 2).arg(p.y(), 0, 'f', 2);
}

QString pathSummary(int turns, double length_m, double time_s) {
  return QStringLiteral("%1 turns, %2 m, %3 s")
      .arg(turns)
      .arg(length_m, 0, 'f', 2)
      .arg(time_s, 0, 'f', 1);
}

// A monotonic clock for the planners' budget (core has no clock of its own).
std::function<double()> wallClock() {
  auto timer = std::make_shared<QElapsedTimer>();
  timer->start();
  return [timer] { return static_cast<double>(timer->nsecsElapsed()) * 1e-9; };
}

}  // namespace

PlanningController::PlanningController(SessionController& session, MapCanvas& canvas,
                                       PlanningPanel& panel, QObject* parent)
    : QObject(parent), session_(session), canvas_(canvas), panel_(panel) {
  behaviours_ = new BehaviourController(session_, this);
  // Plan with the speeds the robot will drive at (its segments primitive: the mission's cruise
  // speed, the robot's default turn rate), so the estimated times are its times.
  settings_.time_model.speed_mps = travelConfig(0.0).speed_mps;
  settings_.time_model.turn_rate_radps = std::min(motion::MotionSettings{}.turn_rate_radps,
                                                  session_.profile().limits.max_turn_rate_radps);
  connectAll();
  setRunning(Running::kNone);
}

PlanningController::~PlanningController() = default;

void PlanningController::connectAll() {
  connect(&panel_, &PlanningPanel::pickGoalToggled, this, [this](bool on) {
    panel_.setSelectRegionChecked(false);
    canvas_.setInteraction(on ? MapCanvas::Interaction::kPickGoal
                              : MapCanvas::Interaction::kNavigate);
  });
  connect(&panel_, &PlanningPanel::selectRegionToggled, this, [this](bool on) {
    panel_.setPickGoalChecked(false);
    canvas_.setInteraction(on ? MapCanvas::Interaction::kSelectRegion
                              : MapCanvas::Interaction::kNavigate);
  });
  connect(&canvas_, &MapCanvas::interactionChanged, this, [this](MapCanvas::Interaction mode) {
    panel_.setPickGoalChecked(mode == MapCanvas::Interaction::kPickGoal);
    panel_.setSelectRegionChecked(mode == MapCanvas::Interaction::kSelectRegion);
  });
  connect(&canvas_, &MapCanvas::worldClicked, this,
          [this](double x, double y) { planGoal(Vec2(x, y)); });
  connect(&canvas_, &MapCanvas::regionSelected, this,
          [this](double x0, double y0, double x1, double y1) {
            Box2 box;
            box.extend(Vec2(x0, y0));
            box.extend(Vec2(x1, y1));
            planRegion(box);
          });
  connect(&panel_, &PlanningPanel::currentTabChanged, this, [this] { refreshOverlay(); });
  connect(&panel_, &PlanningPanel::driveGoalRequested, this, [this] { driveGoal(); });
  connect(&panel_, &PlanningPanel::driveCoverageRequested, this, [this] { driveCoverage(); });
  connect(&panel_, &PlanningPanel::stopRequested, this,
          [this] { stopAll(tr("stopped by the user")); });
  connect(&panel_, &PlanningPanel::coverageSettingsChanged, this, [this] {
    if (region_ && running_ != Running::kCoverage)
      planRegion(*region_);
  });
  connect(&panel_, &PlanningPanel::planSourceChanged, this, [this] {
    if (running_ != Running::kNone)
      return;
    if (goal_)
      planGoal(*goal_);
    if (region_)
      planRegion(*region_);
  });
  connect(&panel_, &PlanningPanel::mapBuildStartRequested, this, [this] { startMapBuilding(); });
  connect(&panel_, &PlanningPanel::mapBuildPauseToggled, this,
          [this](bool paused) { setMapBuildingPaused(paused); });
  connect(&panel_, &PlanningPanel::mapBuildAbortRequested, this,
          [this] { stopAll(tr("aborted by the user")); });
  connect(&panel_, &PlanningPanel::saveBuiltMapRequested, this,
          &PlanningController::saveBuiltMapInteractively);

  connect(behaviours_, &BehaviourController::message, this, [this](const QString& text) {
    session_.report(EventLevel::kInfo, behaviours_->label() + QStringLiteral(": ") + text);
  });
  connect(behaviours_, &BehaviourController::sampleConsumed, this, &PlanningController::onSample);
  connect(behaviours_, &BehaviourController::finished, this,
          &PlanningController::onBehaviourFinished);
  connect(&session_, &SessionController::ticked, this, &PlanningController::refreshLive);
  connect(&session_, &SessionController::worldLoaded, this, [this] {
    world_grids_.reset();
    goal_.reset();
    goal_preview_.reset();
    region_.reset();
    coverage_preview_.reset();
    sweep_.reset();
    built_grid_.reset();
    built_indices_.clear();
    panel_.setBuiltMapAvailable(false);
    showGoalPreview();
    showCoveragePreview();
  });
}

std::optional<Pose2> PlanningController::robotPose() const {
  const auto& sample = session_.latestSample();
  if (!sample)
    return std::nullopt;
  return sample->odometry_pose;
}

void PlanningController::setSettings(const PlanningSettings& settings) {
  const TravelTimeModel time_model = settings_.time_model;
  settings_ = settings;
  settings_.time_model = time_model;
  world_grids_.reset();  // the resolution or clearance may have changed
}

std::optional<PlanningGrids> PlanningController::currentGrids() {
  const double radius = session_.profile().bodyRadius();
  try {
    switch (panel_.planSource()) {
      case PlanSource::kWorldMap:
        if (!world_grids_)
          world_grids_ = gridsFromWorld(session_.worldMap(), radius, settings_);
        return world_grids_;
      case PlanSource::kSonarGrid:
        return gridsFromOccupancy(session_.grid(), radius, settings_, "sonar grid");
      case PlanSource::kBuiltMap:
        if (const MapBuildingMission* building = mapBuilding())
          return gridsFromOccupancy(building->grid(), radius, settings_, "built map");
        if (built_grid_)
          return gridsFromOccupancy(*built_grid_, radius, settings_, "built map");
        session_.report(EventLevel::kWarning, tr("No built map yet: run map building first"));
        return std::nullopt;
    }
  } catch (const std::exception& e) {
    session_.report(EventLevel::kError, tr("Cannot plan on this map: %1").arg(e.what()));
  }
  return std::nullopt;
}

bool PlanningController::planGoal(const Vec2& goal) {
  goal_ = goal;
  goal_preview_.reset();
  const auto pose = robotPose();
  auto grids = currentGrids();
  if (!pose || !grids) {
    showGoalPreview();
    return false;
  }
  goal_preview_ = previewGoal(*grids, *pose, goal, settings_, wallClock());
  showGoalPreview();
  const GoalPreview& p = *goal_preview_;
  if (!p.ok) {
    session_.report(EventLevel::kWarning,
                    tr("Goal %1 on the %2: %3")
                        .arg(point(goal), QString::fromStdString(grids->source),
                             QString::fromStdString(p.error)));
    return false;
  }
  session_.report(
      EventLevel::kInfo,
      tr("Goal %1 on the %2: A* %3; amended %4 (planned in %5 ms, %6 expansions)%7")
          .arg(point(p.goal), QString::fromStdString(grids->source),
               pathSummary(p.raw_turns, p.raw_length_m, p.raw_time_s),
               pathSummary(p.amended_turns, p.amended_length_m, p.amended_time_s))
          .arg(p.planning_time_s * 1e3, 0, 'f', 1)
          .arg(p.expansions)
          .arg(p.error.empty() ? QString()
                               : QStringLiteral("; ") + QString::fromStdString(p.error)));
  return true;
}

bool PlanningController::driveGoal() {
  if (!goal_ || running_ != Running::kNone)
    return false;
  if (!planGoal(*goal_))  // from where the robot is now
    return false;
  std::shared_ptr<TravelMission> travel;
  try {
    // A goal path also stops for what the map did not show (forward sonars); coverage lanes
    // end near walls on purpose, so they rely on the bumpers and the watchdog only.
    travel = std::make_shared<TravelMission>(turningPoints(goal_preview_->travel),
                                             travelConfig(kGoalStopDistance_m));
  } catch (const std::exception& e) {
    session_.report(EventLevel::kError, tr("Cannot drive this path: %1").arg(e.what()));
    return false;
  }
  driven_path_ = goal_preview_->amended;
  reached_ = 0;
  const std::size_t segments = goal_preview_->travel.segments.size();
  if (!startBehaviour(Running::kGoal, travel, nullptr, tr("Goal")))
    return false;
  session_.report(EventLevel::kInfo,
                  tr("Driving to %1: %2 segments").arg(point(goal_preview_->goal)).arg(segments));
  refreshOverlay();
  return true;
}

bool PlanningController::planRegion(const Box2& region) {
  region_ = region;
  coverage_preview_.reset();
  sweep_.reset();
  const auto pose = robotPose();
  auto grids = currentGrids();
  if (!pose || !grids) {
    showCoveragePreview();
    return false;
  }
  coverage_preview_ = previewCoverage(*grids, *pose, region, panel_.coveragePattern(),
                                      panel_.laneWidth(), settings_, wallClock());
  showCoveragePreview();
  const CoveragePreview& c = *coverage_preview_;
  if (!c.ok) {
    session_.report(EventLevel::kWarning, tr("Coverage of %1–%2: %3")
                                              .arg(point(region.min), point(region.max),
                                                   QString::fromStdString(c.error)));
    return false;
  }
  session_.report(
      EventLevel::kInfo,
      tr("Coverage of %1–%2 (%3): %4 m of lanes, %5 turns, about %6 s; planned cover %7 %")
          .arg(point(c.region.min), point(c.region.max),
               panel_.coveragePattern() == CoveragePattern::kSpiral ? tr("spiral")
                                                                    : tr("boustrophedon"))
          .arg(c.coverage.length_m, 0, 'f', 1)
          .arg(c.coverage.turns)
          .arg(c.time_s, 0, 'f', 0)
          .arg(c.coverage.coverage * 100.0, 0, 'f', 1));
  return true;
}

bool PlanningController::driveCoverage() {
  if (!region_ || running_ != Running::kNone)
    return false;
  if (!planRegion(*region_))
    return false;
  const CoveragePreview& c = *coverage_preview_;
  std::shared_ptr<TravelMission> travel;
  try {
    travel = std::make_shared<TravelMission>(turningPoints(c.travel), travelConfig(0.0));
    sweep_.emplace(c.region_raw, c.region_inflated, c.region_start,
                   session_.profile().bodyRadius());
  } catch (const std::exception& e) {
    session_.report(EventLevel::kError, tr("Cannot drive this coverage path: %1").arg(e.what()));
    return false;
  }
  driven_path_ = c.path;
  reached_ = 0;
  const std::size_t segments = c.travel.segments.size();
  if (!startBehaviour(Running::kCoverage, travel, nullptr, tr("Coverage"))) {
    sweep_.reset();
    return false;
  }
  session_.report(EventLevel::kInfo, tr("Covering the region: %1 segments").arg(segments));
  refreshLive();
  return true;
}

bool PlanningController::startMapBuilding() {
  if (running_ != Running::kNone)
    return false;
  std::shared_ptr<MapBuildingMission> building;
  try {
    building = std::make_shared<MapBuildingMission>(session_.profile());
  } catch (const std::exception& e) {
    session_.report(EventLevel::kError, tr("Map building cannot run: %1").arg(e.what()));
    return false;
  }
  shown_indices_ = 0;
  const QString where = robotPose() ? point(robotPose()->position()) : QStringLiteral("?");
  if (!startBehaviour(Running::kMapBuilding, nullptr, building, tr("Map building")))
    return false;
  session_.report(EventLevel::kInfo, tr("Map building started at %1").arg(where));
  refreshLive();
  return true;
}

bool PlanningController::startBehaviour(Running running, std::shared_ptr<TravelMission> travel,
                                        std::shared_ptr<MapBuildingMission> building,
                                        const QString& label) {
  std::shared_ptr<Mission> mission = building;
  if (!mission)
    mission = travel;
  // Set first: a behaviour with nothing to do finishes inside start(), and its end is shown as
  // this task's.
  setRunning(running);
  std::swap(travel_, travel);
  std::swap(building_, building);
  if (behaviours_->start(std::move(mission), label, ActivityRunner::Policy::kRefuseIfBusy))
    return true;
  // Refused (another activity drives the robot; the runner said so): the last run stays shown.
  setRunning(Running::kNone);
  travel_ = std::move(travel);
  building_ = std::move(building);
  return false;
}

void PlanningController::setMapBuildingPaused(bool paused) {
  if (running_ != Running::kMapBuilding)
    return;
  behaviours_->setPaused(paused);
  panel_.setRunningTask(PlanningPanel::Task::kMapBuilding, behaviours_->paused());
  session_.report(EventLevel::kInfo,
                  paused ? tr("Map building paused") : tr("Map building resumed"));
}

void PlanningController::stopAll(const QString& reason) {
  if (behaviours_->running())
    behaviours_->abort(reason);
}

TravelMissionConfig PlanningController::travelConfig(double stop_distance_m) const {
  TravelMissionConfig config;
  config.speed_mps =
      std::min(TravelMissionConfig{}.speed_mps, session_.profile().limits.max_speed_mps);
  config.turn_quantum_rad = settings_.turn_quantum_rad;
  config.stop_distance_m = stop_distance_m;
  return config;
}

const MapBuildingMission* PlanningController::mapBuilding() const {
  return building_.get();
}

std::optional<double> PlanningController::coverage() const {
  if (!sweep_)
    return std::nullopt;
  return sweep_->coverage();
}

void PlanningController::onSample(const TelemetrySample& sample) {
  if (running_ == Running::kCoverage && sweep_)
    sweep_->addPosition(sample.odometry_pose.position());
}

void PlanningController::onBehaviourFinished(bool failed, const QString& message) {
  const Running was = running_;
  setRunning(Running::kNone);
  const QString label = behaviours_->label();
  const EventLevel level = failed ? EventLevel::kWarning : EventLevel::kInfo;
  if (was == Running::kGoal) {
    QString where;
    if (const auto pose = robotPose(); pose && goal_preview_)
      where = tr(" (%1 m from the goal by odometry)")
                  .arg((pose->position() - goal_preview_->goal).norm(), 0, 'f', 3);
    session_.report(level, label + QStringLiteral(": ") + message + where);
  } else if (was == Running::kCoverage) {
    session_.report(level, tr("%1: %2; swept %3 % of the region")
                               .arg(label, message)
                               .arg(sweep_ ? sweep_->coverage() * 100.0 : 0.0, 0, 'f', 1));
  } else if (was == Running::kMapBuilding) {
    keepBuiltGrid();
    session_.report(level, label + QStringLiteral(": ") + message);
  } else {
    session_.report(level, label + QStringLiteral(": ") + message);
  }
  refreshLive();
}

void PlanningController::keepBuiltGrid() {
  if (const MapBuildingMission* building = mapBuilding()) {
    built_grid_ = building->grid();
    built_indices_ = building->allIndices();
    panel_.setBuiltMapAvailable(!built_grid_->observedCellRect().empty());
  }
}

void PlanningController::setRunning(Running running) {
  running_ = running;
  switch (running) {
    case Running::kNone:
      panel_.setRunningTask(PlanningPanel::Task::kNone);
      break;
    case Running::kGoal:
      panel_.setRunningTask(PlanningPanel::Task::kGoal);
      break;
    case Running::kCoverage:
      panel_.setRunningTask(PlanningPanel::Task::kCoverage);
      break;
    case Running::kMapBuilding:
      panel_.setRunningTask(PlanningPanel::Task::kMapBuilding);
      break;
  }
}

void PlanningController::showGoalPreview() {
  if (!goal_preview_ || !goal_preview_->ok) {
    panel_.setGoalPreview(std::nullopt, std::nullopt,
                          goal_preview_ ? QString::fromStdString(goal_preview_->error)
                                        : tr("Pick a goal on the map."));
    panel_.setGoalDrivable(false);
  } else {
    const GoalPreview& p = *goal_preview_;
    QString note = tr("Goal %1: amendment saves %2 turns, %3 s")
                       .arg(point(p.goal))
                       .arg(p.raw_turns - p.amended_turns)
                       .arg(p.raw_time_s - p.amended_time_s, 0, 'f', 1);
    if (!p.error.empty())
      note += QStringLiteral("\n") + QString::fromStdString(p.error);
    panel_.setGoalPreview(
        PlanningPanel::PathStats{p.raw_turns, p.raw_length_m, p.raw_time_s},
        PlanningPanel::PathStats{p.amended_turns, p.amended_length_m, p.amended_time_s}, note);
    panel_.setGoalDrivable(true);
  }
  refreshOverlay();
  emit goalPreviewChanged();
}

void PlanningController::showCoveragePreview() {
  if (!coverage_preview_ || !coverage_preview_->ok) {
    panel_.setCoverageSummary(coverage_preview_ ? QString::fromStdString(coverage_preview_->error)
                                                : tr("Select a region on the map."));
    panel_.setCoverageDrivable(false);
  } else {
    const CoveragePreview& c = *coverage_preview_;
    panel_.setCoverageSummary(tr("%1 × %2 m region: %3 m path, %4 turns, ~%5 s; plan covers %6 %")
                                  .arg(c.region.size().x(), 0, 'f', 2)
                                  .arg(c.region.size().y(), 0, 'f', 2)
                                  .arg(pathLength(c.path), 0, 'f', 1)
                                  .arg(countTurns(c.path))
                                  .arg(c.time_s, 0, 'f', 0)
                                  .arg(c.coverage.coverage * 100.0, 0, 'f', 0));
    panel_.setCoverageDrivable(true);
  }
  panel_.setCoverage(coverage());
  refreshOverlay();
  emit coveragePreviewChanged();
}

void PlanningController::refreshOverlay() {
  // The current tab's items, and those of the running task (a coverage run stays visible while
  // the user looks at the goal tab).
  const PlanningPanel::Tab tab = panel_.currentTab();
  const bool goal = tab == PlanningPanel::Tab::kGoal || running_ == Running::kGoal;
  const bool cover = tab == PlanningPanel::Tab::kCoverage || running_ == Running::kCoverage;
  const bool build = tab == PlanningPanel::Tab::kMapBuilding || running_ == Running::kMapBuilding;
  widgets::PlanningOverlay overlay;
  if (goal && goal_)
    overlay.goal = goal_preview_ && goal_preview_->ok ? goal_preview_->goal : *goal_;
  if (goal && goal_preview_ && goal_preview_->ok) {
    overlay.raw_path = goal_preview_->raw;
    overlay.amended_path = goal_preview_->amended;
  }
  if (cover && region_)
    overlay.region =
        coverage_preview_ && coverage_preview_->ok ? coverage_preview_->region : *region_;
  if (cover && coverage_preview_ && coverage_preview_->ok)
    overlay.coverage_path = coverage_preview_->path;
  if (build) {
    if (const MapBuildingMission* building = mapBuilding())
      overlay.indices = building->allIndices();
    else
      overlay.indices = built_indices_;
  }
  if (running_ == Running::kGoal)
    overlay.reached = reached_;
  canvas_.setPlanningOverlay(std::move(overlay));
}

void PlanningController::refreshLive() {
  const BehaviourStatus status = behaviours_->status();
  if (travel_) {
    if (travel_->reached() != reached_ && running_ == Running::kGoal) {
      reached_ = travel_->reached();
      refreshOverlay();
    }
  }
  if (running_ == Running::kCoverage || sweep_)
    panel_.setCoverage(coverage());
  if (const MapBuildingMission* building = mapBuilding()) {
    QString phase = QString::fromStdString(status.phase);
    if (running_ == Running::kMapBuilding && behaviours_->paused())
      phase += tr(" (paused)");
    if (building->obstacleCount() > 0)
      phase += tr(" — %1 obstacle(s)").arg(building->obstacleCount());
    panel_.setMapBuildStatus(phase, status.progress);
    if (building->allIndices().size() != shown_indices_) {
      shown_indices_ = building->allIndices().size();
      refreshOverlay();
    }
    if (running_ == Running::kMapBuilding && !built_grid_)
      panel_.setBuiltMapAvailable(!building->grid().observedCellRect().empty());
  }
}

std::optional<QString> PlanningController::saveBuiltMap(const QString& yaml_path) {
  const OccupancyGrid* grid = nullptr;
  if (const MapBuildingMission* building = mapBuilding())
    grid = &building->grid();
  else if (built_grid_)
    grid = &*built_grid_;
  if (grid == nullptr)
    return tr("there is no built map yet: run map building first");
  GridExportThresholds thresholds;
  thresholds.padding_cells = 5;
  if (const auto error =
          saveGridAsRosMap(*grid, std::filesystem::path(yaml_path.toStdString()), thresholds))
    return QString::fromStdString(*error);
  session_.report(EventLevel::kInfo,
                  tr("Built map saved as %1 (+ .pgm)").arg(QFileInfo(yaml_path).fileName()));
  return std::nullopt;
}

void PlanningController::saveBuiltMapInteractively() {
  const QString path =
      QFileDialog::getSaveFileName(canvas_.window(), tr("Save Built Map"),
                                   QStringLiteral("built_map.yaml"), tr("ROS map (*.yaml)"));
  if (path.isEmpty())
    return;
  if (const auto error = saveBuiltMap(path))
    session_.report(EventLevel::kError, tr("Cannot save the built map: %1").arg(*error));
}

}  // namespace irgs::gui
