#include "comms/robot/linked_robot.hpp"

#include <boost/asio/post.hpp>
#include <boost/asio/steady_timer.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <future>
#include <stdexcept>
#include <utility>
#include <variant>

#include "comms/robot/teleop_pacer.hpp"

namespace irgs::comms {

namespace mav = mavlink;

namespace {

using Clock = std::chrono::steady_clock;

// Period of the io-thread timer that re-sends MANUAL_CONTROL and releases held samples.
constexpr double kTimerPeriod_s = 0.01;

std::int16_t axis(double fraction) {
  return static_cast<std::int16_t>(std::lround(std::clamp(fraction, -1.0, 1.0) * 1000.0));
}

bool isZero(const VelocityCommand& c) {
  return c.linear_mps == 0.0 && c.angular_radps == 0.0;
}

void requireFinite(double value, const char* what) {
  if (!std::isfinite(value))
    throw std::invalid_argument(std::string("behaviour command: ") + what + " is not finite");
}

void requireNonNegative(double value, const char* what) {
  requireFinite(value, what);
  if (value < 0.0)
    throw std::invalid_argument(std::string("behaviour command: ") + what + " is negative");
}

}  // namespace

mav::ManualControl manualControlFor(const VelocityCommand& command, const MotionLimits& limits,
                                    std::uint8_t target_system) {
  if (!std::isfinite(command.linear_mps) || !std::isfinite(command.angular_radps))
    throw std::invalid_argument("manualControlFor: non-finite velocity");
  if (!(limits.max_speed_mps > 0.0) || !(limits.max_turn_rate_radps > 0.0))
    throw std::invalid_argument("manualControlFor: limits must be > 0");
  mav::ManualControl mc;
  mc.target = target_system;
  mc.x = axis(command.linear_mps / limits.max_speed_mps);
  // MAVLink r > 0 turns clockwise; our omega is counter-clockwise positive.
  mc.r = axis(-command.angular_radps / limits.max_turn_rate_radps);
  return mc;
}

mav::CommandLong behaviourCommandLong(const RobotBehaviourCommand& command,
                                      std::uint8_t target_system) {
  mav::CommandLong c;
  c.target_system = target_system;
  switch (command.kind) {
    case RobotBehaviourKind::kMoveDistance:
      requireFinite(command.distance_m, "distance");
      requireNonNegative(command.speed_mps, "speed");
      c.command = static_cast<std::uint16_t>(mav::MavCmd::kIrgsMoveDistance);
      c.param1 = static_cast<float>(command.distance_m);
      c.param2 = static_cast<float>(command.speed_mps);
      break;
    case RobotBehaviourKind::kTurnAngle:
      requireFinite(command.angle_rad, "angle");
      requireNonNegative(command.turn_rate_radps, "turn rate");
      c.command = static_cast<std::uint16_t>(mav::MavCmd::kIrgsTurnAngle);
      c.param1 = static_cast<float>(command.angle_rad);
      c.param2 = static_cast<float>(command.turn_rate_radps);
      break;
    case RobotBehaviourKind::kFollowWall:
      requireNonNegative(command.distance_m, "wall distance");
      requireNonNegative(command.speed_mps, "speed");
      requireNonNegative(command.travel_m, "travel");
      c.command = static_cast<std::uint16_t>(mav::MavCmd::kIrgsFollowWall);
      c.param1 = static_cast<float>(command.distance_m);
      c.param2 = command.wall_on_left ? 0.0f : 1.0f;  // IRGS_WALL_SIDE: 0 left, 1 right
      c.param3 = static_cast<float>(command.speed_mps);
      c.param4 = static_cast<float>(command.travel_m);
      break;
    case RobotBehaviourKind::kStop:
      c.command = static_cast<std::uint16_t>(mav::MavCmd::kIrgsStop);
      break;
    case RobotBehaviourKind::kEmergencyStop:
      c.command = static_cast<std::uint16_t>(mav::MavCmd::kIrgsEmergencyStop);
      c.param1 = command.engage ? 1.0f : 0.0f;
      break;
  }
  return c;
}

// Shared between the robot's owner thread and the io thread. Everything below `mutex` is
// guarded by it; the rest is touched on the io thread only.
struct LinkedRobot::State : std::enable_shared_from_this<LinkedRobot::State> {
  State(IoThread& io_thread, const RobotProfile& profile, const LinkedRobotConfig& cfg)
      : io(io_thread),
        config(cfg),
        limits(profile.limits),
        own_system(cfg.link.session.system_id),
        robot_system(cfg.link.session.target_system),
        assembler(profile, cfg.telemetry),
        timer(io_thread.context()),
        epoch(Clock::now()),
        pacer({cfg.teleop_period_s, cfg.teleop_min_interval_s}),
        messages(cfg.messages) {}

  double now() const { return std::chrono::duration<double>(Clock::now() - epoch).count(); }

  // ---- io thread ----
  void arm() {
    if (timer_stopped)
      return;
    timer.expires_after(
        std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(kTimerPeriod_s)));
    timer.async_wait([self = shared_from_this()](const boost::system::error_code& ec) {
      if (ec || self->timer_stopped)
        return;
      self->onTimer();
      self->arm();
    });
  }

  void stopTimer() {
    timer_stopped = true;
    timer.cancel();
  }

  void onTimer() {
    const double t = now();
    assembler.tick(t);
    const std::lock_guard lock(mutex);
    moveReadyLocked();
    params.setTarget(robot_system);
    params.tick(t);
    flushParamsLocked();
    pumpTeleopLocked(t);  // a change held back by the interval, or the 10 Hz repeat
    motion->tick();
  }

  void onFrame(const mav::Frame& frame) {
    if (frame.system_id == own_system)
      return;  // our own frames echoed back
    if (robot_system == 0) {
      // Lock on the first robot, as LinkSession does: a heartbeat that is not a ground station's.
      if (const auto hb = frame.as<mav::Heartbeat>();
          hb && hb->type != static_cast<std::uint8_t>(mav::MavType::kGcs)) {
        robot_system = frame.system_id;
        motion->setTargetSystem(frame.system_id);
      } else {
        return;
      }
    }
    if (frame.system_id != robot_system)
      return;
    if (messages.enabled()) {
      const std::lock_guard lock(mutex);
      messages.onFrame(frame, now());
    }
    if (const auto value = frame.as<mav::ParamValue>()) {
      const std::lock_guard lock(mutex);
      params.onParamValue(*value, now());
      return;
    }
    if (frame.message_id == mav::IrgsMotionReport::kId ||
        frame.message_id == mav::IrgsBehaviourStatus::kId)
      motion->onFrame(frame);
    assembler.onFrame(frame, now());
    if (assembler.hasReady()) {
      const std::lock_guard lock(mutex);
      moveReadyLocked();
    }
  }

  void onEvent(const LinkEvent& event) {
    const std::lock_guard lock(mutex);
    if (event.kind == LinkEventKind::kLinkUp) {
      assembler.reset();  // the robot may have restarted: new time base
      messages.reset();
    }
    moveReadyLocked();
    motion->onLinkEvent(event);
    pushEventLocked(event);
    if ((event.kind == LinkEventKind::kLinkLost || event.kind == LinkEventKind::kClosed) &&
        !isZero(command)) {
      command = {};
      pacer.cancel();
      LinkEvent cleared;
      cleared.kind = LinkEventKind::kTransport;
      cleared.time_s = event.time_s;
      cleared.state = event.state;
      cleared.severity = static_cast<std::uint8_t>(mav::MavSeverity::kWarning);
      cleared.text = "teleop command cleared (link down): drive again when the link is back";
      pushEventLocked(std::move(cleared));
    }
  }

  // ---- any thread, mutex held ----
  void moveReadyLocked() {
    std::vector<TelemetrySample> ready = assembler.takeReady();
    if (!ready.empty())
      motion->onSample(ready.back().time_s, ready.back().odometry_pose);
    for (TelemetrySample& s : ready) {
      samples.push_back(std::move(s));
      if (samples.size() > std::max<std::size_t>(1, config.max_pending_samples)) {
        samples.pop_front();
        ++dropped_samples;
      }
    }
  }

  void pushEventLocked(LinkEvent event) {
    events.push_back(std::move(event));
    if (events.size() > std::max<std::size_t>(1, config.max_pending_events))
      events.pop_front();
  }

  void flushParamsLocked() {
    for (const ParamOutgoing& message : params.takeOutgoing()) {
      if (link != nullptr)
        std::visit([this](const auto& m) { link->send(m); }, message);
    }
  }

  // The newest teleop command; the pacer sends it now or when the interval allows.
  void wantTeleopLocked(const VelocityCommand& wanted, double t) {
    command = wanted;
    const mav::ManualControl mc = manualControlFor(wanted, limits);
    pacer.want({mc.x, mc.r});
    pumpTeleopLocked(t);
  }

  void pumpTeleopLocked(double t) {
    const std::optional<TeleopAxes> axes = pacer.next(t);
    if (!axes || link == nullptr)
      return;
    mav::ManualControl mc;
    mc.target = robot_system;
    mc.x = axes->x;
    mc.r = axes->r;
    link->send(mc);
  }

  IoThread& io;
  const LinkedRobotConfig config;
  const MotionLimits limits;
  const std::uint8_t own_system;

  // io thread only
  std::atomic<std::uint8_t>
      robot_system;  // 0 until the first robot heartbeat (or the configured target)
  TelemetryAssembler assembler;
  boost::asio::steady_timer timer;
  bool timer_stopped = false;
  const Clock::time_point epoch;

  std::mutex mutex;
  Link* link = nullptr;  // set once before the timer starts; valid until the timer is stopped
  std::deque<TelemetrySample> samples;
  std::deque<LinkEvent> events;
  std::uint64_t dropped_samples = 0;
  VelocityCommand command;
  TeleopPacer pacer;
  ParamClient params;
  MessageSampler messages;
  std::shared_ptr<LinkedMotion> motion;  // set once in open(), before any callback
};

LinkedRobot::OpenResult LinkedRobot::open(IoThread& io, const LinkUrl& url, RobotProfile profile,
                                          LinkedRobotConfig config) {
  if (!std::isfinite(config.teleop_period_s) || config.teleop_period_s <= 0.0 ||
      config.teleop_period_s > 0.25)
    return {nullptr,
            "linked robot: teleop_period_s must be in (0, 0.25] s (the firmware stops the motors "
            "when MANUAL_CONTROL pauses for 0.3 s)"};
  if (!std::isfinite(config.teleop_min_interval_s) || config.teleop_min_interval_s <= 0.0 ||
      config.teleop_min_interval_s > config.teleop_period_s)
    return {nullptr, "linked robot: teleop_min_interval_s must be in (0, teleop_period_s]"};
  if (!(profile.limits.max_speed_mps > 0.0) || !(profile.limits.max_turn_rate_radps > 0.0))
    return {nullptr, "linked robot: the robot profile's max speed and turn rate must be > 0"};
  std::shared_ptr<State> state;
  try {
    state = std::make_shared<State>(io, profile, config);
    state->motion = std::make_shared<LinkedMotion>(config.motion, [epoch = state->epoch] {
      return std::chrono::duration<double>(Clock::now() - epoch).count();
    });
  } catch (const std::invalid_argument& e) {
    return {nullptr, std::string("linked robot: ") + e.what()};
  }
  state->motion->setTargetSystem(config.link.session.target_system);
  LinkCallbacks callbacks;
  callbacks.on_frame = [state](const mav::Frame& frame) { state->onFrame(frame); };
  callbacks.on_event = [state](const LinkEvent& event) { state->onEvent(event); };
  LinkResult made = Link::create(io, url, config.link, std::move(callbacks));
  if (!made.link)
    return {nullptr, made.error};

  std::unique_ptr<LinkedRobot> robot(
      new LinkedRobot(std::move(profile), url.toString(), std::move(config)));
  if (const auto baud = linkBaud(url))
    robot->tx_budget_bytes_per_s_ = *baud / 10.0;  // a UART's 10 bits per byte
  robot->state_ = state;
  robot->motion_ = state->motion;
  robot->motion_->attach(made.link.get());
  {
    const std::lock_guard lock(state->mutex);
    state->link = made.link.get();
  }
  robot->link_ = std::move(made.link);
  boost::asio::post(io.context(), [state] { state->arm(); });
  robot->link_->open();
  return {std::move(robot), {}};
}

LinkedRobot::LinkedRobot(RobotProfile profile, std::string url_text, LinkedRobotConfig config)
    : profile_(std::move(profile)), url_text_(std::move(url_text)), config_(std::move(config)) {}

LinkedRobot::~LinkedRobot() {
  motion_->attach(nullptr);  // nothing more is sent through the link about to go
  // Best effort: a robot that was driving gets a zero MANUAL_CONTROL before the link goes (the
  // firmware's teleop expiry stops it anyway).
  {
    const std::lock_guard lock(state_->mutex);
    if (!isZero(state_->command))
      state_->wantTeleopLocked({}, state_->now());  // unless the interval holds it back
  }
  IoThread& io = state_->io;
  if (io.isCurrentThread() || !io.running()) {
    state_->stopTimer();
  } else {
    std::promise<void> done;
    boost::asio::post(io.context(), [&done, state = state_] {
      state->stopTimer();
      done.set_value();
    });
    done.get_future().wait();
  }
  {
    const std::lock_guard lock(state_->mutex);
    state_->link = nullptr;
  }
  link_.reset();  // waits until no link callback runs any more
}

const RobotProfile& LinkedRobot::profile() const {
  return profile_;
}

std::string LinkedRobot::describe() const {
  return url_text_ + " (" + std::string(toString(link_->state())) + ")";
}

void LinkedRobot::drive(const VelocityCommand& command) {
  if (!std::isfinite(command.linear_mps) || !std::isfinite(command.angular_radps))
    throw std::invalid_argument("LinkedRobot::drive: non-finite velocity");
  const std::lock_guard lock(state_->mutex);
  // A change goes out at once unless the last MANUAL_CONTROL is younger than the interval (then
  // the timer sends the newest); an unchanged non-zero one keeps its 10 Hz rhythm. Calling
  // drive() every millisecond does not flood the link.
  state_->wantTeleopLocked(command, state_->now());
}

void LinkedRobot::stop() {
  {
    const std::lock_guard lock(state_->mutex);
    state_->wantTeleopLocked({}, state_->now());  // zero MANUAL_CONTROL: ends teleop
  }
  link_->sendCommand(behaviourCommandLong({.kind = RobotBehaviourKind::kStop}));
}

std::vector<TelemetrySample> LinkedRobot::update(double /*wall_elapsed_s*/) {
  // The robot's clock runs on its own; update() only drains what arrived.
  std::vector<TelemetrySample> out;
  const std::lock_guard lock(state_->mutex);
  out.reserve(state_->samples.size());
  for (auto& s : state_->samples)
    out.push_back(std::move(s));
  state_->samples.clear();
  if (!out.empty())
    motion_->samplesDelivered(out.back().time_s);  // reports up to it may be taken now
  return out;
}

MotionControl* LinkedRobot::motionControl() {
  return motion_.get();
}

std::vector<TelemetrySample> LinkedRobot::finish() {
  link_->close();
  // Runs after the close on the io thread: no byte is taken in any more, so what the assembler
  // holds is all there is.
  const auto release = [state = state_] {
    state->stopTimer();
    state->assembler.reset();
    const std::lock_guard lock(state->mutex);
    state->moveReadyLocked();
  };
  IoThread& io = state_->io;
  if (io.isCurrentThread() || !io.running()) {
    release();
  } else {
    std::promise<void> done;
    boost::asio::post(io.context(), [&done, &release] {
      release();
      done.set_value();
    });
    done.get_future().wait();
  }
  return update(0.0);
}

LinkState LinkedRobot::linkState() const {
  return link_->state();
}

LinkStats LinkedRobot::linkStats() const {
  LinkStats stats = link_->stats();
  stats.tx_budget_bytes_per_s = tx_budget_bytes_per_s_;
  return stats;
}

std::vector<LinkEvent> LinkedRobot::takeEvents() {
  const std::lock_guard lock(state_->mutex);
  std::vector<LinkEvent> out(std::make_move_iterator(state_->events.begin()),
                             std::make_move_iterator(state_->events.end()));
  state_->events.clear();
  return out;
}

std::uint64_t LinkedRobot::droppedSamples() const {
  const std::lock_guard lock(state_->mutex);
  return state_->dropped_samples;
}

std::vector<MessageSample> LinkedRobot::takeMessages() {
  const std::lock_guard lock(state_->mutex);
  return state_->messages.take();
}

MessageSamplerCounters LinkedRobot::messageCounters() const {
  const std::lock_guard lock(state_->mutex);
  return state_->messages.counters();
}

void LinkedRobot::sendBehaviour(const RobotBehaviourCommand& command, CommandCallback done) {
  const mav::CommandLong c = behaviourCommandLong(command);  // throws before anything is sent
  if (command.kind == RobotBehaviourKind::kStop ||
      command.kind == RobotBehaviourKind::kEmergencyStop) {
    const std::lock_guard lock(state_->mutex);
    if (!isZero(state_->command))
      state_->wantTeleopLocked({}, state_->now());
  } else {
    // A behaviour replaces teleop on the robot: no MANUAL_CONTROL may follow it (a non-neutral
    // one would end the behaviour), so whatever the pacer still held is dropped.
    const std::lock_guard lock(state_->mutex);
    state_->command = {};
    state_->pacer.cancel();
  }
  link_->sendCommand(c, std::move(done));
}

void LinkedRobot::requestParams() {
  const std::lock_guard lock(state_->mutex);
  state_->params.setTarget(state_->robot_system);
  state_->params.requestAll(state_->now());
  state_->flushParamsLocked();
}

void LinkedRobot::setParam(const std::string& name, double value) {
  const std::lock_guard lock(state_->mutex);
  state_->params.setTarget(state_->robot_system);
  state_->params.set(name, value, state_->now());  // throws before anything is sent
  state_->flushParamsLocked();
}

std::vector<ParamEntry> LinkedRobot::firmwareParams() const {
  const std::lock_guard lock(state_->mutex);
  return state_->params.params();
}

int LinkedRobot::firmwareParamCount() const {
  const std::lock_guard lock(state_->mutex);
  return state_->params.expectedCount();
}

bool LinkedRobot::readingParams() const {
  const std::lock_guard lock(state_->mutex);
  return state_->params.reading();
}

std::vector<ParamWriteResult> LinkedRobot::takeParamResults() {
  const std::lock_guard lock(state_->mutex);
  return state_->params.takeResults();
}

}  // namespace irgs::comms
