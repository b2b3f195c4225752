#pragma once
// One ground-station session: the robot (simulated or behind a link — this class only sees the
// Robot interface and its capabilities), the world map, the robot profile, and the occupancy grid
// built from the robot's sonar. A ~60 Hz timer advances the robot by the real elapsed time,
// integrates every sample into the grid and reports the newest state and notable events. What
// drives the robot on its own (a behaviour, a drive script, a mission) runs in the session's one
// ActivityRunner, which sees every sample and is asked for the command before every robot update.

#include <QElapsedTimer>
#include <QObject>
#include <QString>
#include <QTimer>
#include <deque>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "app/gui/activity_runner.hpp"
#include "core/mapping/occupancy_grid.hpp"
#include "core/mapping/sonar_mapper.hpp"
#include "core/robot/robot.hpp"
#include "core/world/world_map.hpp"

namespace irgs::gui {

enum class EventLevel { kInfo, kWarning, kError, kSensor };

// Builds the robot for a world. Called again when the map changes or the robot is reset to its
// start pose; the robot starts at map.start.
using RobotFactory =
    std::function<std::unique_ptr<Robot>(const WorldMap& map, const RobotProfile& profile)>;

class SessionController : public QObject {
  Q_OBJECT

 public:
  // Timer period (~60 Hz) and per-tick limits that keep the GUI responsive at speed "max".
  static constexpr int kTickInterval_ms = 16;
  static constexpr double kMaxTickElapsed_s = 0.25;  // longer stalls (dialogs) are not replayed
  static constexpr double kTickBudget_s = 0.010;     // robot updates + grid work per tick
  static constexpr std::size_t kMaxPendingSamples = 400;  // backlog that pauses the robot
  static constexpr int kMaxUpdatesPerTick = 64;           // robot->update() calls per tick
  static constexpr double kSensorLinePeriod_s = 0.5;      // sensor console lines, wall time

  SessionController(RobotProfile profile, RobotFactory factory, QObject* parent = nullptr);
  ~SessionController() override;

  // Replaces the world: a new robot at the map's start pose, an empty grid. `source` names the
  // file for the console and the window title. The robot's pause state and speed carry over.
  // Throws what the factory throws (a map the simulator cannot use); the session is then
  // unchanged.
  void loadWorld(WorldMap map, const QString& source);
  // Replaces the map in place (the map editor): the robot, its pose, the grid and the source
  // stay; a simulated robot's world is swapped (SimulatedWorld::setWorld) so the simulator runs
  // on what is being edited. A linked robot does not use the map. Emits worldEdited().
  void updateWorld(WorldMap map);
  // Replaces the robot factory and, with a robot from it, the robot (simulator <-> linked
  // robot). Throws what the factory throws (std::invalid_argument for an empty factory); the
  // session is then unchanged.
  void setRobotFactory(RobotFactory factory);
  const RobotFactory& robotFactory() const { return factory_; }

  const WorldMap& worldMap() const { return map_; }
  const QString& worldSource() const { return source_; }
  const RobotProfile& profile() const { return profile_; }
  const OccupancyGrid& grid() const { return grid_; }
  // Mapping parameters (the parameters panel). A different grid resolution starts an empty grid
  // (gridReset()); the sonar valid distance (nullopt: each sonar's max range) applies from the
  // next sample. Throws std::invalid_argument as OccupancyGrid / SonarMapper do; the session is
  // then unchanged.
  void setMappingParameters(double grid_resolution_m, std::optional<double> valid_distance_m);
  std::optional<double> sonarValidDistance_m() const { return valid_distance_m_; }
  // Integrates every sample still waiting (a slow machine may be behind the robot), so what is
  // written at exit holds all the robot sent — as a replay of the session's recording will.
  void integrateAllPending();
  // Ends the session with the robot (Robot::finish: a linked robot closes its link) and
  // integrates everything it delivered. Call once, at exit, before the recording is closed.
  void finishRobot();
  Robot* robot() { return robot_.get(); }
  // Null when the robot's clock is not ours (a linked robot).
  SimulationControl* simulationControl();
  // Null when the robot's world is not simulated here (a linked robot).
  SimulatedWorld* simulatedWorld();
  const std::optional<TelemetrySample>& latestSample() const { return latest_; }
  // Time of the newest sample shown (integrated), s; monotonic across robot resets.
  double displayTime_s() const { return display_time_s_; }
  // Session time of the current robot's time zero: a sample's session time is its robot time
  // plus this (for data that comes from the robot beside its samples, e.g. link messages).
  double robotTimeOffset_s() const { return time_offset_s_; }
  // Time of the newest sample the robot produced (may run ahead of the display under load).
  double robotTime_s() const { return robot_time_s_; }
  bool paused() const { return paused_; }
  double speedFactor() const { return speed_factor_; }
  const VelocityCommand& command() const { return command_; }
  std::size_t pendingSamples() const { return pending_.size(); }

  // The one owner of what drives the robot on its own. It gets every sample the robot produces,
  // in order, as soon as advanceRobot() receives it (before the next command query and before
  // the sample is integrated): an activity sees each sample exactly once and its answer applies
  // from the next robot step. It is asked for the command before every robot update with the
  // robot's session time, and answers with the time of the next change: the session splits
  // robot updates there, so with a simulator at a finite speed every change takes effect on the
  // step it is due, however the GUI ticks.
  ActivityRunner& runner() { return *runner_; }

  // Starts/stops the periodic timer (tests drive tick() directly instead).
  void start();
  void stopTicking();
  // One timer tick with an explicit elapsed wall time, s.
  void tick(double wall_elapsed_s);

 public slots:
  void drive(double linear_mps, double angular_radps);
  void stopRobot();
  void setPaused(bool paused);
  void singleStep();
  void setSpeedFactor(double factor);  // 0 = max
  void resetRobotToStart();            // a fresh robot (same factory, same seed) at the start pose
  void resetGrid();
  // Adds a line to the console stream (for other parts of the app: file actions, modes).
  void report(irgs::gui::EventLevel level, const QString& text);

 signals:
  void worldLoaded();
  void worldEdited();    // updateWorld(): the same world, edited
  void robotReplaced();  // a new robot at the start pose (map loaded or reset): trails restart
  // The newest integrated sample, once per tick; at fast speeds also intermediate samples
  // (every few centimetres of travel) so a view's trail follows the path.
  void robotStateChanged(const irgs::TelemetrySample& sample);
  // Every sample, in order, as it is integrated into the grid (and the start pose's synthetic
  // one after robotReplaced): for estimators, which must see each step, not the display rate's
  // subset (at x10 a 100 Hz robot is shown at 60 Hz: one sample in 16).
  void sampleIntegrated(const irgs::TelemetrySample& sample);
  // Cells changed since the previous signal (the session takes the grid's dirty rect).
  void gridChanged(const irgs::OccupancyGrid::CellRect& dirty_cells);
  void gridReset();                 // the grid was replaced: redraw everything
  void mappingParametersChanged();  // setMappingParameters() applied new values
  void consoleEvent(irgs::gui::EventLevel level, double time_s, const QString& text);
  void pausedChanged(bool paused);
  void speedFactorChanged(double factor);
  void ticked();

 private:
  void onTimer();
  std::unique_ptr<Robot> makeRobot(const WorldMap& map) const;
  void installRobot(std::unique_ptr<Robot> robot);
  void applySimulationSettings();
  // Runs the robot for `wall_s` of wall time (split at schedule changes), queueing its samples.
  void advanceRobot(double wall_s, const QElapsedTimer& tick_clock);
  // Applies the runner's command for the robot's time; returns the next change time.
  double applySchedule();
  // Integrates pending samples until the tick budget is used (at least one); returns how many.
  std::size_t integratePending(const QElapsedTimer& tick_clock);
  std::size_t integratePending(const QElapsedTimer& tick_clock, qint64 budget_ns);
  void noteEvents(const TelemetrySample& sample);
  void maybeEmitSensorLine();

  RobotProfile profile_;
  RobotFactory factory_;
  SonarMapper mapper_;
  std::optional<double> valid_distance_m_;
  std::unique_ptr<Robot> robot_;
  WorldMap map_;
  QString source_;
  QString mode_;  // robot->describe() of the current robot, reported when it changes
  OccupancyGrid grid_;

  QTimer timer_;
  QElapsedTimer wall_clock_;
  QElapsedTimer sensor_line_clock_;
  bool paused_ = false;
  double speed_factor_ = 1.0;
  VelocityCommand command_;

  std::deque<TelemetrySample> pending_;
  std::optional<TelemetrySample> latest_;
  std::vector<std::optional<SonarReading>> last_sonar_;  // newest reading per sensor
  double time_offset_s_ = 0.0;  // session time of the current robot's time zero
  double display_time_s_ = 0.0;
  double robot_time_s_ = 0.0;
  double step_s_ = 0.01;                     // the robot's sample spacing, learnt from samples
  Vec2 last_shown_position_ = Vec2::Zero();  // odometry position last sent to the view
  std::uint32_t last_bumpers_ = 0;
  bool blocked_ = false;  // commanded to move but not moving, with a bumper pressed
  double blocked_since_s_ = 0.0;
  bool sensor_line_due_ = false;
  // Last: destroyed first, while the session it calls is still whole.
  std::unique_ptr<ActivityRunner> runner_ = std::make_unique<ActivityRunner>(*this);
};

}  // namespace irgs::gui
