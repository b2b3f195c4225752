#include "app/robot/firmware_core.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

#include "comms/mavlink/messages.hpp"

namespace irgs::app {

namespace mav = comms::mavlink;

namespace {

std::uint32_t toBootMs(double t_s) {
  return static_cast<std::uint32_t>(std::llround(std::max(0.0, t_s) * 1000.0));
}

std::uint64_t toBootUs(double t_s) {
  return static_cast<std::uint64_t>(std::llround(std::max(0.0, t_s) * 1e6));
}

std::uint16_t toCentimetres(double metres) {
  return static_cast<std::uint16_t>(std::clamp(std::lround(metres * 100.0), 0L, 65534L));
}

std::uint16_t toMillimetres(double metres) {
  return static_cast<std::uint16_t>(std::clamp(std::lround(metres * 1000.0), 0L, 65534L));
}

// MAVLink sensor yaw rotations count clockwise in 45 degree steps; our heading is CCW.
std::uint8_t sensorOrientation(double heading_rad) {
  const double cw_deg = -radToDeg(heading_rad);
  const double steps = std::round(cw_deg / 45.0);
  if (std::abs(cw_deg - steps * 45.0) > 1.0)
    return static_cast<std::uint8_t>(mav::MavSensorOrientation::kCustom);
  const long index = ((static_cast<long>(steps) % 8) + 8) % 8;  // 0 = kNone .. 7 = kYaw315
  return static_cast<std::uint8_t>(index);
}

// MANUAL_CONTROL axis -> [-1, 1]; INT16_MAX marks an unused axis (treated as centred).
double axis(std::int16_t value) {
  if (value == std::numeric_limits<std::int16_t>::max())
    return 0.0;
  return std::clamp(static_cast<double>(value) / 1000.0, -1.0, 1.0);
}

constexpr std::uint8_t kSeverityCritical = static_cast<std::uint8_t>(mav::MavSeverity::kCritical);
constexpr std::uint8_t kSeverityWarning = static_cast<std::uint8_t>(mav::MavSeverity::kWarning);
constexpr std::uint8_t kSeverityInfo = static_cast<std::uint8_t>(mav::MavSeverity::kInfo);

}  // namespace

FirmwareConfig slowLinkFirmwareConfig(FirmwareConfig base) {
  base.odometry_period_s = 0.1;
  base.sonar_period_s = 0.2;
  base.contact_period_s = 1.0;
  base.send_odometry = false;
  base.send_local_position = false;
  base.send_pose_2d = true;
  base.send_sonar_scan = true;
  base.send_distance_sensor = false;
  base.send_encoder_ticks = false;
  return base;
}

FirmwareCore::FirmwareCore(Simulator simulator, FirmwareConfig config)
    : sim_(std::move(simulator)),
      config_(config),
      encoder_(config.system_id, config.component_id),
      fresh_sonar_(sim_.profile().sonars.size()),
      last_sonar_(sim_.profile().sonars.size()) {
  if (!(config_.teleop_timeout_s > 0.0) || !(config_.gcs_timeout_s > 0.0))
    throw std::invalid_argument("FirmwareConfig: timeouts must be positive");
  if (!(config_.heartbeat_period_s > 0.0) || !(config_.odometry_period_s >= 0.0) ||
      !(config_.sonar_period_s >= 0.0) || !(config_.contact_period_s >= 0.0))
    throw std::invalid_argument("FirmwareConfig: periods must be non-negative (heartbeat > 0)");
  for (std::size_t i = 0; i < last_sonar_.size(); ++i) {
    last_sonar_[i].sensor = static_cast<int>(i);
  }
  const double t = sim_.time_s();
  next_heartbeat_s_ = next_odometry_s_ = next_sonar_s_ = next_contact_s_ = t;
}

template <class M>
void FirmwareCore::send(const M& message) {
  const mav::EncodedFrame frame = encoder_.encode(message);
  const auto bytes = frame.view();
  output_.insert(output_.end(), bytes.begin(), bytes.end());
}

void FirmwareCore::sendStatus(std::uint8_t severity, const std::string& text) {
  mav::Statustext m;
  m.severity = severity;
  const std::size_t n = std::min(text.size(), m.text.size());
  std::copy_n(text.begin(), n, m.text.begin());
  send(m);
}

std::vector<std::uint8_t> FirmwareCore::takeOutput() {
  std::vector<std::uint8_t> out;
  out.swap(output_);
  return out;
}

void FirmwareCore::receiveBytes(std::span<const std::uint8_t> bytes, double now_s) {
  frames_.clear();
  decoder_.feed(bytes, frames_);
  for (const auto& frame : frames_)
    receive(frame, now_s);
}

void FirmwareCore::receive(const mav::Frame& frame, double now_s) {
  if (frame.system_id == config_.system_id)
    return;  // our own frames echoed back (a pty in echo mode): never a ground station
  if (auto hb = frame.as<mav::Heartbeat>()) {
    // Any other system's heartbeat counts as the ground station's (MAV_TYPE_GCS from QGC,
    // MAVProxy, IRGS; hand-written tools often leave the type at 0).
    if (!last_gcs_heartbeat_s_ || now_s > *last_gcs_heartbeat_s_)
      last_gcs_heartbeat_s_ = now_s;
    warned_no_gcs_ = false;
  } else if (auto mc = frame.as<mav::ManualControl>()) {
    if (mc->target != 0 && mc->target != config_.system_id)
      return;
    if (!last_gcs_heartbeat_s_ || now_s - *last_gcs_heartbeat_s_ > config_.gcs_timeout_s) {
      if (!warned_no_gcs_)
        sendStatus(kSeverityWarning, "MANUAL_CONTROL ignored: no GCS heartbeat");
      warned_no_gcs_ = true;
      return;
    }
    const MotionLimits& limits = sim_.profile().limits;
    teleop_.linear_mps = axis(mc->x) * limits.max_speed_mps;
    // MAVLink r > 0 turns clockwise (right); our omega is counter-clockwise positive.
    teleop_.angular_radps = -axis(mc->r) * limits.max_turn_rate_radps;
    last_teleop_s_ = now_s;
    if (teleop_.linear_mps != 0.0 || teleop_.angular_radps != 0.0)
      endBehaviour(mav::IrgsBehaviourState::kAborted);  // the operator takes over
  } else if (auto cmd = frame.as<mav::CommandLong>()) {
    if (cmd->target_system != 0 && cmd->target_system != config_.system_id)
      return;
    handleCommand(*cmd);
  }
}

void FirmwareCore::handleCommand(const mav::CommandLong& command) {
  mav::CommandAck ack;
  ack.command = command.command;
  ack.result = static_cast<std::uint8_t>(mav::MavResult::kUnsupported);
  switch (static_cast<mav::MavCmd>(command.command)) {
    case mav::MavCmd::kIrgsStop:
      endBehaviour(mav::IrgsBehaviourState::kAborted);
      teleop_ = {};
      last_teleop_s_.reset();
      sim_.setCommand({});  // controlled stop: decelerate at the profile's limits
      ack.result = static_cast<std::uint8_t>(mav::MavResult::kAccepted);
      sendStatus(kSeverityInfo, "stop");
      break;
    case mav::MavCmd::kIrgsEmergencyStop:
      if (command.param1 >= 0.5f) {
        estop_ = true;
        safetyStop("EMERGENCY STOP engaged");
      } else if (estop_) {
        estop_ = false;
        last_teleop_s_.reset();  // motion needs a fresh command after a release
        sendStatus(kSeverityWarning, "emergency stop released");
      }
      ack.result = static_cast<std::uint8_t>(mav::MavResult::kAccepted);
      break;
    case mav::MavCmd::kIrgsMoveDistance:
    case mav::MavCmd::kIrgsTurnAngle:
      ack.result = startBehaviour(command);
      break;
    default:
      break;  // wall following, parameters, missions: not implemented by this firmware yet
  }
  send(ack);
}

void FirmwareCore::safetyStop(const std::string& reason) {
  endBehaviour(mav::IrgsBehaviourState::kAborted);
  sim_.halt();
  sendStatus(estop_ ? kSeverityCritical : kSeverityWarning, reason);
}

SafetyState FirmwareCore::safety() const {
  SafetyState s;
  const double t = sim_.time_s();
  s.gcs_alive = last_gcs_heartbeat_s_ && t - *last_gcs_heartbeat_s_ <= config_.gcs_timeout_s;
  s.teleop_active = last_teleop_s_ && t - *last_teleop_s_ <= config_.teleop_timeout_s;
  s.estop_latched = estop_;
  s.bumpers = bumpers_;
  const auto& bumpers = sim_.profile().bumpers;
  for (std::size_t i = 0; i < bumpers.size() && i < 32; ++i) {
    if ((bumpers_ >> i) & 1u) {
      // A bumper facing forward blocks forward motion, one facing backward blocks reversing.
      const double facing = std::cos(bumpers[i].normal_rad);
      s.forward_blocked = s.forward_blocked || facing > 1e-6;
      s.reverse_blocked = s.reverse_blocked || facing < -1e-6;
    }
  }
  return s;
}

void FirmwareCore::applySafety() {
  const SafetyState s = safety();
  if (gcs_was_alive_ && !s.gcs_alive) {
    last_teleop_s_.reset();
    safetyStop("GCS heartbeat lost: motors stopped");
  } else if (teleop_was_active_ && !s.teleop_active && s.gcs_alive && !estop_ &&
             behaviour_.state != mav::IrgsBehaviourState::kRunning) {
    if (teleop_.linear_mps != 0.0 || teleop_.angular_radps != 0.0)
      safetyStop("teleop timeout: motors stopped");
    else
      sim_.halt();
  }
  gcs_was_alive_ = s.gcs_alive;
  teleop_was_active_ = s.teleop_active && s.gcs_alive;

  VelocityCommand command;
  const std::optional<VelocityCommand> behaviour = behaviourCommand();
  if (behaviour && s.gcs_alive && !estop_) {
    command = *behaviour;
  } else if (s.gcs_alive && s.teleop_active && !estop_) {
    command = teleop_;
    if ((s.forward_blocked && command.linear_mps > 0.0) ||
        (s.reverse_blocked && command.linear_mps < 0.0))
      command.linear_mps = 0.0;
  }
  sim_.setCommand(command);
}

void FirmwareCore::advance(double now_s) {
  const double dt = sim_.config().dt_s;
  while (sim_.time_s() + 0.5 * dt <= now_s) {
    applySafety();
    sim_.step(sample_);
    const std::uint32_t pressed = sample_.bumpers & ~bumpers_;
    const bool changed = sample_.bumpers != bumpers_;
    bumpers_ = sample_.bumpers;
    if (pressed != 0) {
      std::string names;
      const auto& bumpers = sim_.profile().bumpers;
      for (std::size_t i = 0; i < bumpers.size() && i < 32; ++i) {
        if ((pressed >> i) & 1u)
          names += (names.empty() ? "" : ",") + bumpers[i].name;
      }
      safetyStop("bumper " + names + ": stopped");
    }
    if (changed)
      next_contact_s_ = sample_.time_s;  // report contact changes at once
    sendTelemetry(sample_);
  }
}

void FirmwareCore::sendTelemetry(const TelemetrySample& sample) {
  const double t = sample.time_s;
  for (const SonarReading& r : sample.sonar) {
    if (r.sensor < 0 || static_cast<std::size_t>(r.sensor) >= fresh_sonar_.size())
      continue;
    fresh_sonar_[static_cast<std::size_t>(r.sensor)] = r;
    last_sonar_[static_cast<std::size_t>(r.sensor)] = r;
    last_sonar_time_s_ = t;
  }
  // A small tolerance so that periods that are multiples of dt do not slip a step on rounding.
  const double eps = 1e-9;
  if (t + eps >= next_heartbeat_s_) {
    sendHeartbeat();
    next_heartbeat_s_ += config_.heartbeat_period_s;
    if (next_heartbeat_s_ <= t)
      next_heartbeat_s_ = t + config_.heartbeat_period_s;
  }
  auto due = [&](double period, double& next) {
    if (period <= 0.0 || t + eps < next)
      return false;
    next += period;
    if (next <= t)
      next = t + period;
    return true;
  };
  if (due(config_.odometry_period_s, next_odometry_s_))
    sendOdometry(sample);
  if (due(config_.sonar_period_s, next_sonar_s_))
    sendSonar(sample);
  if (due(config_.contact_period_s, next_contact_s_))
    sendContact(sample);
  if (behaviour_.state == mav::IrgsBehaviourState::kRunning &&
      t + eps >= next_behaviour_status_s_) {
    sendBehaviourStatus();
    next_behaviour_status_s_ = t + 0.5;  // 2 Hz while running
  }
}

std::uint8_t FirmwareCore::startBehaviour(const mav::CommandLong& command) {
  const bool move = command.command == static_cast<std::uint16_t>(mav::MavCmd::kIrgsMoveDistance);
  const double target = static_cast<double>(command.param1);
  const double speed = static_cast<double>(command.param2);
  if (!std::isfinite(target) || !std::isfinite(speed) || speed < 0.0)
    return static_cast<std::uint8_t>(mav::MavResult::kDenied);
  if (estop_)
    return static_cast<std::uint8_t>(mav::MavResult::kDenied);
  const SafetyState s = safety();
  if (!s.gcs_alive)
    return static_cast<std::uint8_t>(mav::MavResult::kTemporarilyRejected);
  if (move && ((s.forward_blocked && target > 0.0) || (s.reverse_blocked && target < 0.0)))
    return static_cast<std::uint8_t>(mav::MavResult::kTemporarilyRejected);
  const MotionLimits& limits = sim_.profile().limits;
  const double max = move ? limits.max_speed_mps : limits.max_turn_rate_radps;
  endBehaviour(mav::IrgsBehaviourState::kAborted);  // a new behaviour replaces the old one
  behaviour_ = {};
  behaviour_.command = command.command;
  behaviour_.state = mav::IrgsBehaviourState::kRunning;
  behaviour_.target = target;
  behaviour_.speed = speed > 0.0 ? std::min(speed, max) : 0.5 * max;  // default: half speed
  behaviour_.last_pose = sim_.odometryPose();
  teleop_ = {};
  last_teleop_s_.reset();
  teleop_was_active_ = false;  // the behaviour replaces teleop: no teleop-expiry stop
  next_behaviour_status_s_ = sim_.time_s();
  return static_cast<std::uint8_t>(mav::MavResult::kAccepted);
}

void FirmwareCore::endBehaviour(mav::IrgsBehaviourState state) {
  if (behaviour_.state != mav::IrgsBehaviourState::kRunning)
    return;
  behaviour_.state = state;
  sim_.setCommand({});
  sendBehaviourStatus();
}

// Progress from odometry; the speed is shaped v = min(speed, sqrt(2 a remaining)) so the robot
// brakes at the profile's deceleration and ends on the target instead of overshooting.
std::optional<VelocityCommand> FirmwareCore::behaviourCommand() {
  if (behaviour_.state != mav::IrgsBehaviourState::kRunning)
    return std::nullopt;
  const bool move =
      behaviour_.command == static_cast<std::uint16_t>(mav::MavCmd::kIrgsMoveDistance);
  const Pose2& pose = sim_.odometryPose();
  const Pose2& last = behaviour_.last_pose;
  if (move) {
    behaviour_.progress +=
        (pose.x - last.x) * std::cos(last.theta) + (pose.y - last.y) * std::sin(last.theta);
  } else {
    behaviour_.progress += wrapAngle(pose.theta - last.theta);
  }
  behaviour_.last_pose = pose;
  const double remaining = behaviour_.target - behaviour_.progress;
  const double tolerance = move ? 0.005 : degToRad(0.5);
  if (std::abs(remaining) <= tolerance || remaining * behaviour_.target < 0.0) {
    endBehaviour(mav::IrgsBehaviourState::kSucceeded);
    return std::nullopt;
  }
  const MotionLimits& limits = sim_.profile().limits;
  const double accel = move ? limits.max_accel_mps2 : limits.max_turn_accel_radps2;
  const double magnitude = std::min(behaviour_.speed, std::sqrt(2.0 * accel * std::abs(remaining)));
  const double signed_speed = remaining > 0.0 ? magnitude : -magnitude;
  VelocityCommand command;
  (move ? command.linear_mps : command.angular_radps) = signed_speed;
  return command;
}

void FirmwareCore::sendBehaviourStatus() {
  mav::IrgsBehaviourStatus status;
  status.time_boot_ms = toBootMs(sim_.time_s());
  status.command = behaviour_.command;
  status.state = static_cast<std::uint8_t>(behaviour_.state);
  status.progress = static_cast<float>(behaviour_.progress);
  send(status);
}

void FirmwareCore::sendHeartbeat() {
  mav::Heartbeat hb;
  hb.type = static_cast<std::uint8_t>(mav::MavType::kGroundRover);
  hb.autopilot = static_cast<std::uint8_t>(mav::MavAutopilot::kGeneric);
  // base_mode, custom_mode and system_status as docs/protocol.md section 2 defines them.
  const SafetyState s = safety();
  const bool teleop = s.gcs_alive && s.teleop_active && !estop_;
  hb.base_mode = static_cast<std::uint8_t>(mav::MavModeFlag::kCustomModeEnabled);
  if (teleop)
    hb.base_mode |= static_cast<std::uint8_t>(mav::MavModeFlag::kManualInputEnabled);
  if (!estop_)
    hb.base_mode |= static_cast<std::uint8_t>(mav::MavModeFlag::kSafetyArmed);
  const bool behaviour = behaviour_.state == mav::IrgsBehaviourState::kRunning;
  hb.custom_mode = estop_ ? 4u : behaviour ? 2u : teleop ? 1u : 0u;
  const VelocityCommand v = sim_.trueVelocity();
  const bool moving = v.linear_mps != 0.0 || v.angular_radps != 0.0;
  hb.system_status = static_cast<std::uint8_t>(estop_   ? mav::MavState::kEmergency
                                               : moving ? mav::MavState::kActive
                                                        : mav::MavState::kStandby);
  send(hb);
}

void FirmwareCore::sendOdometry(const TelemetrySample& sample) {
  const Pose2& p = sample.odometry_pose;
  const double v = sample.measured_velocity.linear_mps;
  const double omega = sample.measured_velocity.angular_radps;
  if (config_.send_local_position) {
    // FLU -> NED (world x as north): rotation by pi about x (y and yaw change sign).
    mav::LocalPositionNed lp;
    lp.time_boot_ms = toBootMs(sample.time_s);
    lp.x = static_cast<float>(p.x);
    lp.y = static_cast<float>(-p.y);
    lp.vx = static_cast<float>(v * std::cos(p.theta));
    lp.vy = static_cast<float>(-v * std::sin(p.theta));
    send(lp);
    mav::Attitude att;
    att.time_boot_ms = lp.time_boot_ms;
    att.yaw = static_cast<float>(wrapAngle(-p.theta));
    att.yawspeed = static_cast<float>(-omega);
    send(att);
  }
  if (config_.send_odometry)
    sendOdometryMessage(sample);
  if (config_.send_pose_2d) {
    mav::IrgsPose2d pose;
    pose.time_boot_ms = toBootMs(sample.time_s);
    pose.x = static_cast<float>(p.x);
    pose.y = static_cast<float>(p.y);
    pose.theta = static_cast<float>(wrapAngle(p.theta));
    pose.v = static_cast<float>(v);
    pose.omega = static_cast<float>(omega);
    send(pose);
  }
  if (config_.send_encoder_ticks) {
    mav::IrgsEncoderTicks ticks;
    ticks.time_usec = toBootUs(sample.time_s);
    ticks.left_ticks = sample.left_ticks;
    ticks.right_ticks = sample.right_ticks;
    send(ticks);
  }
}

void FirmwareCore::sendOdometryMessage(const TelemetrySample& sample) {
  const Pose2& p = sample.odometry_pose;
  mav::Odometry od;
  od.time_usec = toBootUs(sample.time_s);
  od.frame_id = static_cast<std::uint8_t>(mav::MavFrame::kLocalNed);
  od.child_frame_id = static_cast<std::uint8_t>(mav::MavFrame::kBodyFrd);
  // FLU -> NED: rotation by pi about x (y and yaw change sign).
  od.x = static_cast<float>(p.x);
  od.y = static_cast<float>(-p.y);
  od.z = 0.0f;
  const double yaw = -p.theta;
  od.q = {static_cast<float>(std::cos(0.5 * yaw)), 0.0f, 0.0f,
          static_cast<float>(std::sin(0.5 * yaw))};
  od.vx = static_cast<float>(sample.measured_velocity.linear_mps);
  od.yawspeed = static_cast<float>(-sample.measured_velocity.angular_radps);
  od.pose_covariance[0] = std::numeric_limits<float>::quiet_NaN();  // unknown
  od.velocity_covariance[0] = std::numeric_limits<float>::quiet_NaN();
  od.estimator_type = static_cast<std::uint8_t>(mav::MavEstimatorType::kNaive);
  send(od);
}

void FirmwareCore::sendSonar(const TelemetrySample& sample) {
  const auto& specs = sim_.profile().sonars;
  mav::IrgsSonarScan scan;
  scan.time_boot_ms = toBootMs(last_sonar_time_s_);
  scan.count = static_cast<std::uint8_t>(std::min<std::size_t>(specs.size(), scan.range.size()));
  for (std::size_t i = 0; i < specs.size(); ++i) {
    const SonarSpec& spec = specs[i];
    if (i < scan.range.size()) {
      scan.range[i] = last_sonar_[i].echo ? toMillimetres(last_sonar_[i].range_m)
                                          : std::numeric_limits<std::uint16_t>::max();
      if (fresh_sonar_[i])
        scan.fired = static_cast<std::uint16_t>(scan.fired | (1u << i));
    }
    if (!fresh_sonar_[i] || i > 255 || !config_.send_distance_sensor)
      continue;
    const SonarReading& r = *fresh_sonar_[i];
    mav::DistanceSensor ds;
    ds.time_boot_ms = toBootMs(sample.time_s);
    ds.min_distance = toCentimetres(spec.min_range_m);
    ds.max_distance = toCentimetres(spec.max_range_m);
    // No echo up to the maximum range: max_distance + 1 ("out of range, nothing seen").
    ds.current_distance =
        r.echo ? toCentimetres(r.range_m) : static_cast<std::uint16_t>(ds.max_distance + 1);
    ds.type = static_cast<std::uint8_t>(mav::MavDistanceSensor::kUltrasound);
    ds.id = static_cast<std::uint8_t>(i);
    ds.orientation = sensorOrientation(spec.mount.theta);
    ds.covariance = std::numeric_limits<std::uint8_t>::max();  // unknown
    ds.horizontal_fov = static_cast<float>(spec.beam_width_rad);
    ds.vertical_fov = static_cast<float>(spec.beam_width_rad);
    send(ds);
  }
  std::fill(fresh_sonar_.begin(), fresh_sonar_.end(), std::nullopt);
  if (config_.send_sonar_scan && !specs.empty())
    send(scan);
}

void FirmwareCore::sendContact(const TelemetrySample& sample) {
  mav::IrgsContact c;
  c.time_boot_ms = toBootMs(sample.time_s);
  c.bumpers = sample.bumpers;
  const auto& proximity = sample.proximity_m;
  c.proximity_count =
      static_cast<std::uint8_t>(std::min<std::size_t>(proximity.size(), c.proximity.size()));
  const auto& specs = sim_.profile().proximity;
  for (std::size_t i = 0; i < c.proximity_count; ++i) {
    const bool nothing = i < specs.size() && proximity[i] >= specs[i].max_range_m - 1e-9;
    c.proximity[i] =
        nothing ? std::numeric_limits<std::uint16_t>::max() : toMillimetres(proximity[i]);
  }
  send(c);
}

}  // namespace irgs::app
