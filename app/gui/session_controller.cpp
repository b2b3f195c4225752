#include "app/gui/session_controller.hpp"

#include <QFileInfo>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

#include "app/gui/event_format.hpp"

namespace irgs::gui {
namespace {

// A robot counts as blocked when it is told to move faster than this but moves slower than the
// stall speed, with a bumper pressed, for at least kBlockedDelay_s of its own time.
constexpr double kMovingCommand_mps = 0.02;
constexpr double kStallSpeed_mps = 0.005;
constexpr double kBlockedDelay_s = 0.5;
// Intermediate robot states sent to the view per tick: at least this far apart, at most so many.
constexpr double kTrailSpacing_m = 0.02;
constexpr int kMaxIntermediateStatesPerTick = 500;
// Simulated steps per robot update when a scheduled command change is near at speed "max"
// (the same 20 steps main.cpp gives SimulatedRobot per max-speed update).
constexpr double kMaxSpeedChunkSteps = 20.0;

}  // namespace

SessionController::SessionController(RobotProfile profile, RobotFactory factory, QObject* parent)
    : QObject(parent),
      profile_(std::move(profile)),
      factory_(std::move(factory)),
      mapper_(profile_) {
  if (!factory_)
    throw std::invalid_argument("SessionController needs a robot factory");
  timer_.setInterval(kTickInterval_ms);
  timer_.setTimerType(Qt::PreciseTimer);
  connect(&timer_, &QTimer::timeout, this, &SessionController::onTimer);
}

SessionController::~SessionController() = default;

SimulationControl* SessionController::simulationControl() {
  return robot_ ? robot_->simulationControl() : nullptr;
}

SimulatedWorld* SessionController::simulatedWorld() {
  return robot_ ? robot_->simulatedWorld() : nullptr;
}

void SessionController::loadWorld(WorldMap map, const QString& source) {
  std::unique_ptr<Robot> robot = makeRobot(map);  // may throw: nothing has changed yet
  map_ = std::move(map);
  source_ = source;
  installRobot(std::move(robot));
  resetGrid();
  emit worldLoaded();
  report(EventLevel::kInfo,
         QStringLiteral("Map '%1' (%2): %3 walls, %4 obstacles, start %5")
             .arg(QString::fromStdString(map_.name), QFileInfo(source_).fileName())
             .arg(map_.walls.size())
             .arg(map_.obstacles.size())
             .arg(formatPose(map_.start)));
}

void SessionController::updateWorld(WorldMap map) {
  if (SimulatedWorld* world = simulatedWorld())
    world->setWorld(map);
  map_ = std::move(map);
  emit worldEdited();
}

void SessionController::setRobotFactory(RobotFactory factory) {
  if (!factory)
    throw std::invalid_argument("SessionController needs a robot factory");
  std::unique_ptr<Robot> robot = factory(map_, profile_);  // may throw: nothing changed yet
  if (!robot)
    throw std::logic_error("robot factory returned no robot");
  factory_ = std::move(factory);
  installRobot(std::move(robot));
}

std::unique_ptr<Robot> SessionController::makeRobot(const WorldMap& map) const {
  std::unique_ptr<Robot> robot = factory_(map, profile_);
  if (!robot)
    throw std::logic_error("robot factory returned no robot");
  return robot;
}

void SessionController::installRobot(std::unique_ptr<Robot> robot) {
  // The new robot's clock starts at zero; session time continues from the displayed time.
  time_offset_s_ = std::max(display_time_s_, robot_time_s_);
  robot_time_s_ = display_time_s_ = time_offset_s_;
  robot_ = std::move(robot);
  const QString mode = QString::fromStdString(robot_->describe());
  if (mode != mode_) {
    mode_ = mode;
    report(EventLevel::kInfo, QStringLiteral("Mode: %1").arg(mode));
  }
  pending_.clear();
  latest_.reset();
  last_sonar_.assign(profile_.sonars.size(), std::nullopt);
  last_bumpers_ = 0;
  blocked_ = false;
  command_ = {};
  applySimulationSettings();
  last_shown_position_ = map_.start.position();
  // Show the robot at its start pose right away, even while paused.
  TelemetrySample initial;
  initial.time_s = time_offset_s_;
  initial.odometry_pose = map_.start;
  if (simulationControl() != nullptr)
    initial.true_pose = map_.start;
  latest_ = initial;
  runner_->onRobotReplaced();  // ends what ran on the old robot (a drive script carries on)
  emit robotReplaced();
  emit sampleIntegrated(initial);
  emit robotStateChanged(initial);
}

void SessionController::applySimulationSettings() {
  if (SimulationControl* sim = simulationControl()) {
    sim->setPaused(paused_);
    sim->setSpeedFactor(speed_factor_);
  }
}

void SessionController::start() {
  wall_clock_.start();
  timer_.start();
}

void SessionController::stopTicking() {
  timer_.stop();
}

void SessionController::onTimer() {
  const double elapsed_s = static_cast<double>(wall_clock_.nsecsElapsed()) * 1e-9;
  wall_clock_.restart();
  tick(elapsed_s);
}

void SessionController::tick(double wall_elapsed_s) {
  if (!robot_)
    return;
  QElapsedTimer tick_clock;
  tick_clock.start();
  advanceRobot(std::clamp(wall_elapsed_s, 0.0, kMaxTickElapsed_s), tick_clock);
  if (integratePending(tick_clock) > 0) {
    emit gridChanged(grid_.takeDirtyRect());
    // The view shows every sonar's latest reading: at high speed one tick integrates many
    // samples, and the newest alone holds only the sonars that fired in its step.
    TelemetrySample shown = *latest_;
    shown.sonar.clear();
    for (const auto& reading : last_sonar_) {
      if (reading)
        shown.sonar.push_back(*reading);
    }
    emit robotStateChanged(shown);
  }
  maybeEmitSensorLine();
  emit ticked();
}

double SessionController::applySchedule() {
  // A change due at t applies from the step that starts at t: ask just after the robot's time
  // so floating-point noise in step times (3.9999999 for 4.0) cannot delay it by a step.
  constexpr double kTimeEpsilon_s = 1e-6;
  return runner_->applyCommand(robot_time_s_ + kTimeEpsilon_s);
}

void SessionController::advanceRobot(double wall_s, const QElapsedTimer& tick_clock) {
  SimulationControl* sim = simulationControl();
  const bool max_speed = sim != nullptr && speed_factor_ <= 0.0;
  const double factor = sim != nullptr ? speed_factor_ : 1.0;
  const auto half_budget_ns = static_cast<qint64>(kTickBudget_s * 0.5e9);
  double remaining_s = wall_s;
  for (int update = 0; update < kMaxUpdatesPerTick; ++update) {
    // Back-pressure: while the grid is behind, the robot waits (a simulator at "max" speed runs
    // exactly as fast as the mapping keeps up; a linked robot keeps its data in its own queue).
    if (pending_.size() >= kMaxPendingSamples)
      break;
    const double next_change_s = applySchedule();
    double slice_s = remaining_s;
    if (!max_speed && factor > 0.0 && std::isfinite(next_change_s)) {
      // Stop at the change; at least one step, so every update makes progress.
      const double until_change_s = std::max(next_change_s - robot_time_s_, step_s_);
      slice_s = std::min(slice_s, until_change_s / factor);
    }
    std::vector<TelemetrySample> samples;
    if (max_speed && std::isfinite(next_change_s)) {
      // A scheduled change at "max" speed: run the stretch before it at x1 for exactly its
      // length (in chunks no longer than a max-speed update), so a script replays on the same
      // steps at every speed, as it does headless.
      const double until_change_s = std::max(next_change_s - robot_time_s_, step_s_);
      sim->setSpeedFactor(1.0);
      // Half a step extra: the robot floors elapsed/step, and 1.5 s / 0.01 s may be 149.99999.
      const double chunk_s = std::min(until_change_s, kMaxSpeedChunkSteps * step_s_);
      samples = robot_->update(chunk_s + 0.5 * step_s_);
      sim->setSpeedFactor(0.0);
    } else {
      samples = robot_->update(slice_s);
    }
    remaining_s -= slice_s;
    for (TelemetrySample& sample : samples) {
      sample.time_s += time_offset_s_;
      if (sample.time_s > robot_time_s_) {
        step_s_ = std::clamp(sample.time_s - robot_time_s_, 1e-4, 1.0);
        robot_time_s_ = sample.time_s;
      }
      runner_->onSample(sample);
      pending_.push_back(std::move(sample));
    }
    if (max_speed) {
      // "As fast as possible": whole robot updates while half the tick budget lasts.
      if (samples.empty() || tick_clock.nsecsElapsed() >= half_budget_ns)
        break;
    } else if (remaining_s <= 1e-9) {
      break;
    }
  }
}

std::size_t SessionController::integratePending(const QElapsedTimer& tick_clock) {
  return integratePending(tick_clock, static_cast<qint64>(kTickBudget_s * 1e9));
}

void SessionController::finishRobot() {
  if (robot_) {
    for (TelemetrySample& sample : robot_->finish()) {
      sample.time_s += time_offset_s_;
      robot_time_s_ = std::max(robot_time_s_, sample.time_s);
      runner_->onSample(sample);
      pending_.push_back(std::move(sample));
    }
  }
  integrateAllPending();
}

void SessionController::integrateAllPending() {
  QElapsedTimer clock;
  clock.start();
  if (integratePending(clock, std::numeric_limits<qint64>::max()) > 0)
    emit gridChanged(grid_.takeDirtyRect());
}

std::size_t SessionController::integratePending(const QElapsedTimer& tick_clock, qint64 budget_ns) {
  std::size_t integrated = 0;
  int shown_this_tick = 0;
  // At least one sample per tick, so progress never stops however slow a sample is.
  while (!pending_.empty() && (integrated == 0 || tick_clock.nsecsElapsed() < budget_ns)) {
    TelemetrySample sample = std::move(pending_.front());
    pending_.pop_front();
    mapper_.integrate(sample, grid_);
    for (const SonarReading& reading : sample.sonar) {
      if (reading.sensor >= 0 && static_cast<std::size_t>(reading.sensor) < last_sonar_.size())
        last_sonar_[static_cast<std::size_t>(reading.sensor)] = reading;
    }
    noteEvents(sample);
    display_time_s_ = std::max(display_time_s_, sample.time_s);
    emit sampleIntegrated(sample);
    // Many samples per tick (fast speeds): also show the intermediate ones the robot moved to,
    // so the canvas trail follows the path rather than joining one pose per frame.
    if (!pending_.empty() && shown_this_tick < kMaxIntermediateStatesPerTick &&
        (sample.odometry_pose.position() - last_shown_position_).norm() >= kTrailSpacing_m) {
      last_shown_position_ = sample.odometry_pose.position();
      ++shown_this_tick;
      emit robotStateChanged(sample);
    }
    latest_ = std::move(sample);
    sensor_line_due_ = true;
    ++integrated;
  }
  if (integrated > 0)
    last_shown_position_ = latest_->odometry_pose.position();
  return integrated;
}

void SessionController::noteEvents(const TelemetrySample& sample) {
  if (sample.bumpers != last_bumpers_) {
    if (last_bumpers_ == 0) {
      report(EventLevel::kWarning,
             QStringLiteral("Collision at %1").arg(formatPose(sample.odometry_pose)));
    }
    for (const QString& line : describeBumperChanges(profile_, last_bumpers_, sample.bumpers))
      emit consoleEvent(EventLevel::kInfo, sample.time_s, line);
    last_bumpers_ = sample.bumpers;
  }
  const bool stalled = std::abs(command_.linear_mps) > kMovingCommand_mps &&
                       std::abs(sample.measured_velocity.linear_mps) < kStallSpeed_mps &&
                       sample.bumpers != 0;
  if (!stalled) {
    blocked_ = false;
    blocked_since_s_ = sample.time_s;
  } else if (!blocked_ && sample.time_s - blocked_since_s_ >= kBlockedDelay_s) {
    blocked_ = true;
    emit consoleEvent(EventLevel::kWarning, sample.time_s,
                      QStringLiteral("Robot blocked: commanded %1 m/s but not moving")
                          .arg(command_.linear_mps, 0, 'f', 2));
  }
}

void SessionController::maybeEmitSensorLine() {
  if (!sensor_line_due_ || !latest_)
    return;
  if (sensor_line_clock_.isValid() &&
      static_cast<double>(sensor_line_clock_.elapsed()) < kSensorLinePeriod_s * 1000.0)
    return;
  sensor_line_clock_.start();
  sensor_line_due_ = false;
  emit consoleEvent(EventLevel::kSensor, latest_->time_s, formatPoseLine(*latest_));
  if (!profile_.sonars.empty())
    emit consoleEvent(EventLevel::kSensor, latest_->time_s, formatSonarLine(profile_, last_sonar_));
}

void SessionController::drive(double linear_mps, double angular_radps) {
  if (!robot_ || !std::isfinite(linear_mps) || !std::isfinite(angular_radps))
    return;
  command_ = {linear_mps, angular_radps};
  robot_->drive(command_);
}

void SessionController::stopRobot() {
  if (!robot_)
    return;
  command_ = {};
  robot_->stop();
}

void SessionController::setPaused(bool paused) {
  if (paused == paused_)
    return;
  paused_ = paused;
  applySimulationSettings();
  report(EventLevel::kInfo,
         paused ? QStringLiteral("Simulation paused") : QStringLiteral("Simulation running"));
  emit pausedChanged(paused);
}

void SessionController::singleStep() {
  SimulationControl* sim = simulationControl();
  if (sim == nullptr)
    return;
  setPaused(true);
  sim->singleStep();
  tick(0.0);
}

void SessionController::setSpeedFactor(double factor) {
  if (!std::isfinite(factor) || factor < 0.0 || factor == speed_factor_)
    return;
  speed_factor_ = factor;
  applySimulationSettings();
  report(EventLevel::kInfo, QStringLiteral("Simulation speed %1").arg(formatSpeedFactor(factor)));
  emit speedFactorChanged(factor);
}

void SessionController::resetRobotToStart() {
  if (!robot_)
    return;
  installRobot(makeRobot(map_));
  report(EventLevel::kInfo,
         QStringLiteral("Robot reset to the start pose %1").arg(formatPose(map_.start)));
}

void SessionController::setMappingParameters(double grid_resolution_m,
                                             std::optional<double> valid_distance_m) {
  SonarMapper mapper(profile_, mapper_.model(), valid_distance_m);  // throws: nothing changed
  OccupancyGrid grid(grid_resolution_m);
  mapper_ = std::move(mapper);
  valid_distance_m_ = valid_distance_m;
  if (grid_resolution_m != grid_.resolution_m()) {
    grid_ = std::move(grid);
    emit gridReset();
  }
  emit mappingParametersChanged();
}

void SessionController::resetGrid() {
  grid_ = OccupancyGrid(grid_.resolution_m());
  emit gridReset();
}

void SessionController::report(EventLevel level, const QString& text) {
  emit consoleEvent(level, display_time_s_, text);
}

}  // namespace irgs::gui
