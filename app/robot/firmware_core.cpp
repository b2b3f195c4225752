#include "app/robot/firmware_core.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

#include "comms/mavlink/messages.hpp"
#include "comms/robot/telemetry_messages.hpp"
#include "core/motion/host_adapters.hpp"

namespace irgs::app {

namespace mav = comms::mavlink;

namespace {

// MANUAL_CONTROL axis -> [-1, 1]; INT16_MAX marks an unused axis (treated as centred).
double axis(std::int16_t value) {
  if (value == std::numeric_limits<std::int16_t>::max())
    return 0.0;
  return std::clamp(static_cast<double>(value) / 1000.0, -1.0, 1.0);
}

constexpr std::uint8_t kSeverityCritical = static_cast<std::uint8_t>(mav::MavSeverity::kCritical);
constexpr std::uint8_t kSeverityWarning = static_cast<std::uint8_t>(mav::MavSeverity::kWarning);
constexpr std::uint8_t kSeverityInfo = static_cast<std::uint8_t>(mav::MavSeverity::kInfo);

constexpr std::uint8_t result(mav::MavResult r) {
  return static_cast<std::uint8_t>(r);
}

// MAV_SYS_STATUS_SENSOR bits (common.xml).
constexpr std::uint32_t kSensorGyro = 1u;
constexpr std::uint32_t kSensorAccel = 2u;
constexpr std::uint32_t kSensorMotorOutputs = 32768u;
constexpr std::uint32_t kSensorBattery = 33554432u;
constexpr std::uint32_t kSensorProximity = 67108864u;

constexpr double kStandardGravity = 9.80665;  // m/s^2

std::int16_t toInt16(double value) {
  return static_cast<std::int16_t>(std::clamp(std::lround(value), -32767L, 32767L));
}

double periodFromRate(double hz) {
  return hz > 0.0 ? 1.0 / hz : 0.0;
}

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
  base.send_mouse_counts = false;
  base.send_caster_encoders = false;
  base.imu_period_s = 0.0;
  base.status_period_s = 5.0;
  base.behaviour_status_period_s = 2.0;
  return base;
}

FirmwareCore::FirmwareCore(Simulator simulator, FirmwareConfig config)
    : sim_(std::move(simulator)),
      config_(config),
      encoder_(config.system_id, config.component_id),
      mission_store_(config.system_id, config.component_id),
      fresh_sonar_(sim_.profile().sonars.size()),
      last_sonar_(sim_.profile().sonars.size()),
      imu_rng_(config.imu_seed) {
  if (!(config_.teleop_timeout_s > 0.0) || !(config_.gcs_timeout_s > 0.0))
    throw std::invalid_argument("FirmwareConfig: timeouts must be positive");
  if (!(config_.heartbeat_period_s > 0.0) || !(config_.odometry_period_s >= 0.0) ||
      !(config_.sonar_period_s >= 0.0) || !(config_.contact_period_s >= 0.0) ||
      !(config_.imu_period_s >= 0.0) || !(config_.status_period_s >= 0.0) ||
      !(config_.behaviour_status_period_s > 0.0))
    throw std::invalid_argument("FirmwareConfig: periods must be non-negative (heartbeat > 0)");
  if (!(config_.gyro_noise_radps >= 0.0) || !(config_.accel_noise_mps2 >= 0.0) ||
      !(config_.battery_capacity_ah > 0.0) || !(config_.battery_full_v > config_.battery_empty_v) ||
      !(config_.battery_empty_v > 0.0) || !(config_.battery_idle_a >= 0.0) ||
      !(config_.battery_a_per_mps >= 0.0) || !(config_.battery_a_per_radps >= 0.0))
    throw std::invalid_argument("FirmwareConfig: IMU noise and battery model out of range");
  for (std::size_t i = 0; i < last_sonar_.size(); ++i) {
    last_sonar_[i].sensor = static_cast<int>(i);
  }
  const double t = sim_.time_s();
  next_heartbeat_s_ = t;
  auto stream = [&](std::uint32_t id, ParamId group, bool on, double period) {
    const double p = on ? period : 0.0;
    streams_.push_back({id, group, p, p, t});
  };
  const double pose = config_.odometry_period_s;
  stream(mav::LocalPositionNed::kId, ParamId::kRatePose, config_.send_local_position, pose);
  stream(mav::Attitude::kId, ParamId::kRatePose, config_.send_local_position, pose);
  stream(mav::Odometry::kId, ParamId::kRatePose, config_.send_odometry, pose);
  stream(mav::IrgsPose2d::kId, ParamId::kRatePose, config_.send_pose_2d, pose);
  const RobotProfile& profile = sim_.profile();
  const bool caster_robot = profile.drive.type == DriveType::kThreeCaster;
  const bool mice = sim_.config().mouse_sensors && profile.drive.extra.contains("mouse_sensors");
  stream(mav::IrgsEncoderTicks::kId, ParamId::kRatePose,
         config_.send_encoder_ticks && !caster_robot, pose);
  stream(mav::IrgsMouseCounts::kId, ParamId::kRatePose, config_.send_mouse_counts && mice, pose);
  stream(mav::IrgsCasterEncoders::kId, ParamId::kRatePose,
         config_.send_caster_encoders && caster_robot, pose);
  stream(mav::DistanceSensor::kId, ParamId::kRateSonar, config_.send_distance_sensor,
         config_.sonar_period_s);
  stream(mav::IrgsSonarScan::kId, ParamId::kRateSonar,
         config_.send_sonar_scan && !sim_.profile().sonars.empty(), config_.sonar_period_s);
  stream(mav::IrgsContact::kId, ParamId::kRateContact, true, config_.contact_period_s);
  stream(mav::ScaledImu::kId, ParamId::kRateImu, true, config_.imu_period_s);
  stream(mav::SysStatus::kId, ParamId::kRateStatus, true, config_.status_period_s);

  // Parameters mirror the config; the speed limits are capped by the robot profile.
  const MotionLimits& limits = sim_.profile().limits;
  params_.setRange(ParamId::kMaxSpeed, std::min(0.01, limits.max_speed_mps), limits.max_speed_mps);
  params_.setRange(ParamId::kMaxTurnRate, std::min(0.05, limits.max_turn_rate_radps),
                   limits.max_turn_rate_radps);
  params_.setInitial(ParamId::kTeleopTimeout, config_.teleop_timeout_s);
  params_.setInitial(ParamId::kHbTimeout, config_.gcs_timeout_s);
  params_.setInitial(ParamId::kMaxSpeed, limits.max_speed_mps);
  params_.setInitial(ParamId::kMaxTurnRate, limits.max_turn_rate_radps);
  // A configured timeout outside the parameter range (command line) is kept as configured.
  if (params_.get(ParamId::kTeleopTimeout) != config_.teleop_timeout_s) {
    params_.setRange(ParamId::kTeleopTimeout,
                     std::min(params_.min(ParamId::kTeleopTimeout), config_.teleop_timeout_s),
                     std::max(params_.max(ParamId::kTeleopTimeout), config_.teleop_timeout_s));
    params_.setInitial(ParamId::kTeleopTimeout, config_.teleop_timeout_s);
  }
  if (params_.get(ParamId::kHbTimeout) != config_.gcs_timeout_s) {
    params_.setRange(ParamId::kHbTimeout,
                     std::min(params_.min(ParamId::kHbTimeout), config_.gcs_timeout_s),
                     std::max(params_.max(ParamId::kHbTimeout), config_.gcs_timeout_s));
    params_.setInitial(ParamId::kHbTimeout, config_.gcs_timeout_s);
  }
  syncRateParams();
  if (config_.signing_key) {
    decoder_.setSigningKey(config_.signing_key, /*require_signed=*/true);
    encoder_.enableSigning(*config_.signing_key, /*link_id=*/0);
  }
  motion_ = std::make_unique<FirmwareMotion>(profile, config_.behaviour_status_period_s);
  motion_->setLimits(maxSpeed(), maxTurnRate());
}

template <class M>
void FirmwareCore::send(const M& message) {
  const mav::EncodedFrame frame = encoder_.encode(message, signingTime(sim_.time_s()));
  const auto bytes = frame.view();
  output_.insert(output_.end(), bytes.begin(), bytes.end());
}

std::uint64_t FirmwareCore::signingTime(double t_s) const {
  return config_.signing_time_at_boot +
         static_cast<std::uint64_t>(std::max(t_s, 0.0) *
                                    static_cast<double>(mav::kSigningTicksPerSecond));
}

std::uint64_t FirmwareCore::refusedFrames() const {
  const mav::DecodeCounters& rx = decoder_.totals();
  return rx.unsigned_rejected + rx.bad_signature + rx.replay_rejected;
}

void FirmwareCore::warnGroundStation(const std::string& text) {
  sendStatus(kSeverityWarning, text);
}

// Refused frames reach whoever holds the link: an unsigned ground station learns why nothing
// moves, a signed one that something else is talking.
void FirmwareCore::reportRefusedFrames(double now_s) {
  const std::uint64_t refused = refusedFrames();
  if (refused == refused_reported_ || now_s < next_refusal_report_s_)
    return;
  sendStatus(kSeverityWarning,
             "unsigned/bad signature: " + std::to_string(refused - refused_reported_) +
                 " refused (" + std::to_string(refused) + " total)");
  refused_reported_ = refused;
  next_refusal_report_s_ = now_s + config_.refusal_report_period_s;
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
  if (config_.signing_key)
    decoder_.setSigningClock(signingTime(now_s));
  decoder_.feed(bytes, frames_);
  for (const auto& frame : frames_)
    receive(frame, now_s);
  if (config_.signing_key)
    reportRefusedFrames(now_s);
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
    teleop_forward_ = axis(mc->x);
    teleop_yaw_cw_ = axis(mc->r);  // MAVLink r > 0 turns clockwise (right)
    last_teleop_s_ = now_s;
    if ((teleop_forward_ != 0.0 || teleop_yaw_cw_ != 0.0) && motion_->running()) {
      motion_->cancel(motionNow());  // the operator takes over
      flushMotion();
    }
  } else if (auto cmd = frame.as<mav::CommandLong>()) {
    if (cmd->target_system != 0 && cmd->target_system != config_.system_id)
      return;
    handleCommand(*cmd);
  } else if (auto sync = frame.as<mav::Timesync>()) {
    // A request (tc1 = 0) addressed to us or broadcast: answer with our clock [ns since boot],
    // ts1 mirrored, addressed to the requester (the GCS computes RTT = now - ts1).
    if (sync->tc1 == 0 && (sync->target_system == 0 || sync->target_system == config_.system_id)) {
      mav::Timesync reply;
      reply.tc1 = static_cast<std::int64_t>(std::llround(std::max(now_s, 1e-9) * 1e9));
      reply.ts1 = sync->ts1;
      reply.target_system = frame.system_id;
      reply.target_component = frame.component_id;
      send(reply);
    }
  } else if (auto waypoints = frame.as<mav::IrgsWaypoints>()) {
    if (waypoints->target_system != 0 && waypoints->target_system != config_.system_id)
      return;
    motion_->onWaypoints(*waypoints, motionNow(), motionPermit());
    afterStart();
  } else if (frame.message_id == mav::ParamRequestList::kId ||
             frame.message_id == mav::ParamRequestRead::kId ||
             frame.message_id == mav::ParamSet::kId) {
    handleParam(frame);
  } else {
    handleMission(frame, now_s);
  }
}

VelocityCommand FirmwareCore::teleopCommand() const {
  // Our omega is counter-clockwise positive, MANUAL_CONTROL r clockwise positive.
  return {teleop_forward_ * maxSpeed(), -teleop_yaw_cw_ * maxTurnRate()};
}

double FirmwareCore::maxSpeed() const {
  return params_.get(ParamId::kMaxSpeed);
}

double FirmwareCore::maxTurnRate() const {
  return params_.get(ParamId::kMaxTurnRate);
}

void FirmwareCore::handleCommand(const mav::CommandLong& command) {
  mav::CommandAck ack;
  ack.command = command.command;
  ack.result = result(mav::MavResult::kUnsupported);
  switch (static_cast<mav::MavCmd>(command.command)) {
    case mav::MavCmd::kIrgsStop:
      ack.result = stopCommand(command);
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
      ack.result = result(mav::MavResult::kAccepted);
      break;
    case mav::MavCmd::kIrgsMoveDistance:
    case mav::MavCmd::kIrgsTurnAngle:
    case mav::MavCmd::kIrgsFollowWall:
      ack.result = *motion_->onCommand(command, motionNow(), motionPermit());
      afterStart();
      break;
    case mav::MavCmd::kMissionStart:
      ack.result = startMission(command);
      break;
    case mav::MavCmd::kSetMessageInterval:
      ack.result = setMessageInterval(command);
      break;
    case mav::MavCmd::kRequestMessage:
      // The one message worth asking for: a ground station that lost a final IRGS_MOTION_REPORT
      // and the status after it learns how the primitive ended.
      if (command.param1 == static_cast<float>(mav::IrgsBehaviourStatus::kId)) {
        motion_->requestStatus(sim_.time_s());
        flushMotion();
        ack.result = result(mav::MavResult::kAccepted);
      }
      break;
    default:
      break;  // anything else: MAV_RESULT_UNSUPPORTED
  }
  send(ack);
}

// ---- Parameters ------------------------------------------------------------------------------

void FirmwareCore::sendParam(ParamId id) {
  mav::ParamValue v;
  v.param_id = paramIdField(paramSpecs()[static_cast<std::size_t>(id)].name);
  v.param_value = static_cast<float>(params_.get(id));
  v.param_type = static_cast<std::uint8_t>(mav::MavParamType::kReal32);
  v.param_count = static_cast<std::uint16_t>(ParamTable::size());
  v.param_index = static_cast<std::uint16_t>(id);
  send(v);
}

void FirmwareCore::handleParam(const mav::Frame& frame) {
  auto addressed = [&](std::uint8_t system, std::uint8_t component) {
    return (system == 0 || system == config_.system_id) &&
           (component == 0 || component == config_.component_id);
  };
  if (auto list = frame.as<mav::ParamRequestList>()) {
    if (!addressed(list->target_system, list->target_component))
      return;
    for (std::size_t i = 0; i < ParamTable::size(); ++i)
      sendParam(static_cast<ParamId>(i));
  } else if (auto read = frame.as<mav::ParamRequestRead>()) {
    if (!addressed(read->target_system, read->target_component))
      return;
    std::optional<ParamId> id;
    if (read->param_index >= 0) {
      if (static_cast<std::size_t>(read->param_index) < ParamTable::size())
        id = static_cast<ParamId>(read->param_index);
    } else {
      id = findParam(paramIdToString(read->param_id));
    }
    if (!id) {
      // The parameter protocol has no negative reply; say it for the operator.
      sendStatus(kSeverityWarning,
                 "no parameter " + (read->param_index >= 0 ? "#" + std::to_string(read->param_index)
                                                           : paramIdToString(read->param_id)));
      return;
    }
    sendParam(*id);
  } else if (auto set = frame.as<mav::ParamSet>()) {
    if (!addressed(set->target_system, set->target_component))
      return;
    const std::string name = paramIdToString(set->param_id);
    const std::optional<ParamId> id = findParam(name);
    if (!id) {
      sendStatus(kSeverityWarning, "no parameter " + name);
      return;
    }
    if (set->param_type != 0 &&
        set->param_type != static_cast<std::uint8_t>(mav::MavParamType::kReal32)) {
      sendStatus(kSeverityWarning, name + ": must be sent as REAL32");
      sendParam(*id);  // the unchanged value: the spec's way to refuse
      return;
    }
    if (auto error = params_.set(*id, static_cast<double>(set->param_value))) {
      sendStatus(kSeverityWarning, *error);
    } else {
      applyParam(*id);
    }
    sendParam(*id);
  }
}

void FirmwareCore::applyParam(ParamId id) {
  const double value = params_.get(id);
  switch (id) {
    case ParamId::kTeleopTimeout:
      config_.teleop_timeout_s = value;
      break;
    case ParamId::kHbTimeout:
      config_.gcs_timeout_s = value;
      break;
    case ParamId::kMaxSpeed:
    case ParamId::kMaxTurnRate:
      // Read at every step (teleop); the primitives' defaults and caps follow, a running one
      // slows down at once.
      motion_->setLimits(maxSpeed(), maxTurnRate());
      break;
    case ParamId::kRatePose:
    case ParamId::kRateSonar:
    case ParamId::kRateContact:
    case ParamId::kRateImu:
    case ParamId::kRateStatus: {
      const double period = periodFromRate(value);
      bool any_on = false;
      for (const Stream& st : streams_)
        any_on = any_on || (st.group == id && st.period_s > 0.0);
      // Messages of the group that are on get the new rate; with the group off, the ones the
      // configuration enables come back.
      for (Stream& st : streams_) {
        if (st.group != id)
          continue;
        if (period == 0.0)
          st.period_s = 0.0;
        else if (st.period_s > 0.0 || (!any_on && st.default_period_s > 0.0))
          st.period_s = period;
        st.next_s = sim_.time_s();
      }
      break;
    }
    case ParamId::kCount:
      break;
  }
}

FirmwareCore::Stream* FirmwareCore::findStream(std::uint32_t message_id) {
  for (Stream& st : streams_)
    if (st.message_id == message_id)
      return &st;
  return nullptr;
}

const FirmwareCore::Stream* FirmwareCore::findStream(std::uint32_t message_id) const {
  for (const Stream& st : streams_)
    if (st.message_id == message_id)
      return &st;
  return nullptr;
}

std::optional<double> FirmwareCore::messagePeriod(std::uint32_t message_id) const {
  if (message_id == mav::Heartbeat::kId)
    return config_.heartbeat_period_s;
  if (const Stream* st = findStream(message_id))
    return st->period_s;
  return std::nullopt;
}

// The SR_* parameters show the rate of the first message of their group that is on.
void FirmwareCore::syncRateParams() {
  for (ParamId group : {ParamId::kRatePose, ParamId::kRateSonar, ParamId::kRateContact,
                        ParamId::kRateImu, ParamId::kRateStatus}) {
    double hz = 0.0;
    for (const Stream& st : streams_) {
      if (st.group == group && st.period_s > 0.0) {
        hz = 1.0 / st.period_s;
        break;
      }
    }
    if (hz > params_.max(group))
      params_.setRange(group, params_.min(group), hz);
    params_.setInitial(group, hz);
  }
}

// MAV_CMD_SET_MESSAGE_INTERVAL: param1 message id, param2 interval [us] (-1 off, 0 default).
std::uint8_t FirmwareCore::setMessageInterval(const mav::CommandLong& command) {
  const double id = static_cast<double>(command.param1);
  const double interval_us = static_cast<double>(command.param2);
  if (!std::isfinite(id) || !std::isfinite(interval_us) || id < 0.0 || id != std::floor(id) ||
      interval_us < -1.0)
    return result(mav::MavResult::kDenied);
  const auto message_id = static_cast<std::uint32_t>(id);
  if (message_id == mav::Heartbeat::kId)
    return result(mav::MavResult::kDenied);  // the link state machine depends on 1 Hz
  Stream* st = findStream(message_id);
  if (st == nullptr)
    return result(mav::MavResult::kUnsupported);
  if (interval_us == -1.0) {
    st->period_s = 0.0;
  } else if (interval_us == 0.0) {
    st->period_s = st->default_period_s;
  } else {
    // At most once per simulation step (the firmware's main loop).
    st->period_s = std::max(interval_us * 1e-6, sim_.config().dt_s);
  }
  st->next_s = sim_.time_s();
  syncRateParams();
  return result(mav::MavResult::kAccepted);
}

// ---- Missions ---------------------------------------------------------------------------------

void FirmwareCore::sendMissionReply(const MissionReply& reply) {
  if (reply.request)
    send(*reply.request);
  if (reply.item)
    send(*reply.item);
  if (reply.count)
    send(*reply.count);
  if (reply.ack)
    send(*reply.ack);
  if (!reply.status.empty())
    sendStatus(reply.warning ? kSeverityWarning : kSeverityInfo, reply.status);
}

void FirmwareCore::handleMission(const mav::Frame& frame, double now_s) {
  auto addressed = [&](std::uint8_t system) { return system == 0 || system == config_.system_id; };
  const std::uint8_t sys = frame.system_id;
  const std::uint8_t comp = frame.component_id;
  if (auto count = frame.as<mav::MissionCount>()) {
    if (!addressed(count->target_system))
      return;
    if (motion_->missionRunning()) {
      mav::MissionAck ack;
      ack.target_system = sys;
      ack.target_component = comp;
      ack.type = static_cast<std::uint8_t>(mav::MavMissionResult::kDenied);
      ack.mission_type = count->mission_type;
      send(ack);
      sendStatus(kSeverityWarning, "mission upload refused: a mission is running");
      return;
    }
    sendMissionReply(mission_store_.onCount(*count, sys, comp, now_s));
  } else if (auto item = frame.as<mav::MissionItemInt>()) {
    if (addressed(item->target_system))
      sendMissionReply(mission_store_.onItem(*item, sys, comp, now_s));
  } else if (auto list = frame.as<mav::MissionRequestList>()) {
    if (addressed(list->target_system))
      sendMissionReply(mission_store_.onRequestList(*list, sys, comp));
  } else if (auto request = frame.as<mav::MissionRequestInt>()) {
    if (addressed(request->target_system))
      sendMissionReply(mission_store_.onRequest(*request, sys, comp));
  } else if (auto clear = frame.as<mav::MissionClearAll>()) {
    if (!addressed(clear->target_system))
      return;
    if (motion_->missionRunning()) {
      motion_->cancel(motionNow());
      flushMotion();
    }
    sendMissionReply(mission_store_.onClearAll(*clear, sys, comp));
  }
}

void FirmwareCore::safetyStop(const std::string& reason) {
  motion_->abort(motion::Reason::kSafety, motionNow());
  flushMotion();
  motion_command_ = {};
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
             !motion_->running()) {
    if (teleop_forward_ != 0.0 || teleop_yaw_cw_ != 0.0)
      safetyStop("teleop timeout: motors stopped");
    else
      sim_.halt();
  }
  gcs_was_alive_ = s.gcs_alive;
  teleop_was_active_ = s.teleop_active && s.gcs_alive;

  VelocityCommand command;
  if (motion_->running() && s.gcs_alive && !estop_) {
    command = motion_command_;
  } else if (s.gcs_alive && s.teleop_active && !estop_) {
    command = teleopCommand();
  }
  // Bumpers block motion into the obstacle whoever commands it (the wall follower backs up).
  if ((s.forward_blocked && command.linear_mps > 0.0) ||
      (s.reverse_blocked && command.linear_mps < 0.0))
    command.linear_mps = 0.0;
  sim_.setCommand(command);
}

void FirmwareCore::advance(double now_s) {
  const double dt = sim_.config().dt_s;
  while (sim_.time_s() + 0.5 * dt <= now_s) {
    applySafety();
    sim_.step(sample_);
    updateImuAndBattery(dt);
    if (sample_.mouse) {
      mouse_worst_right_ = std::max(mouse_worst_right_, sample_.mouse->right.status);
      mouse_worst_left_ = std::max(mouse_worst_left_, sample_.mouse->left.status);
    }
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
      // The wheels stop at once; the running primitive sees the contact in this very step and
      // ends (drive, segments, path: kFailed(kBumped)) or backs off (follow wall: kContact).
      sim_.halt();
      sendStatus(kSeverityWarning, "bumper " + names + ": stopped");
    }
    if (changed) {
      if (Stream* contact = findStream(mav::IrgsContact::kId); contact && contact->period_s > 0.0)
        contact->next_s = sample_.time_s;  // report contact changes at once
    }
    motion_command_ = motion_->step(motion::motionInputOf(sample_));
    sendTelemetry(sample_);
    flushMotion();  // the step's reports after its telemetry (docs/protocol.md section 18)
    sendMissionReply(mission_store_.poll(sample_.time_s));
  }
}

// The IMU sees the true motion: forward acceleration from the true velocity's change, the
// centripetal acceleration v * omega, gravity and the yaw rate; the battery drains with it.
void FirmwareCore::updateImuAndBattery(double dt_s) {
  const VelocityCommand v = sim_.trueVelocity();
  accel_forward_mps2_ = (v.linear_mps - last_true_velocity_.linear_mps) / dt_s;
  last_true_velocity_ = v;
  battery_current_a_ = config_.battery_idle_a + config_.battery_a_per_mps * std::abs(v.linear_mps) +
                       config_.battery_a_per_radps * std::abs(v.angular_radps);
  battery_used_ah_ =
      std::min(config_.battery_capacity_ah, battery_used_ah_ + battery_current_a_ * dt_s / 3600.0);
}

double FirmwareCore::batteryRemaining() const {
  return std::clamp(1.0 - battery_used_ah_ / config_.battery_capacity_ah, 0.0, 1.0);
}

void FirmwareCore::sendTelemetry(const TelemetrySample& sample) {
  const double t = sample.time_s;
  for (const SonarReading& r : sample.sonar) {
    if (r.sensor < 0 || static_cast<std::size_t>(r.sensor) >= fresh_sonar_.size())
      continue;
    fresh_sonar_[static_cast<std::size_t>(r.sensor)] = r;
    last_sonar_[static_cast<std::size_t>(r.sensor)] = r;
    if (r.sensor < 16)
      scan_fired_ |= 1u << r.sensor;
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
  for (Stream& st : streams_) {
    if (st.period_s <= 0.0 || t + eps < st.next_s)
      continue;
    st.next_s += st.period_s;
    if (st.next_s <= t)
      st.next_s = t + st.period_s;
    sendStream(st.message_id, sample);
  }
}

void FirmwareCore::sendStream(std::uint32_t message_id, const TelemetrySample& sample) {
  switch (message_id) {
    case mav::LocalPositionNed::kId:
      sendLocalPosition(sample);
      break;
    case mav::Attitude::kId:
      sendAttitude(sample);
      break;
    case mav::Odometry::kId:
      sendOdometryMessage(sample);
      break;
    case mav::IrgsPose2d::kId:
      sendPose2d(sample);
      break;
    case mav::IrgsEncoderTicks::kId:
      sendEncoderTicks(sample);
      break;
    case mav::IrgsMouseCounts::kId:
      sendMouseCounts(sample);
      break;
    case mav::IrgsCasterEncoders::kId:
      sendCasterEncoders(sample);
      break;
    case mav::DistanceSensor::kId:
      sendDistanceSensors(sample);
      break;
    case mav::IrgsSonarScan::kId:
      sendSonarScan();
      break;
    case mav::IrgsContact::kId:
      sendContact(sample);
      break;
    case mav::ScaledImu::kId:
      sendScaledImu(sample);
      break;
    case mav::SysStatus::kId:
      sendSysStatus();
      break;
    default:
      break;
  }
}

// ---- Behaviours: motion primitives (firmware_motion.hpp) ----------------------------------------

motion::MotionInput FirmwareCore::motionNow() const {
  motion::MotionInput in;
  in.time_s = sim_.time_s();
  in.odometry = sim_.odometryPose();
  in.measured = sample_.measured_velocity;
  in.bumpers = bumpers_;
  return in;
}

MotionPermit FirmwareCore::motionPermit() const {
  const SafetyState s = safety();
  return {estop_, s.gcs_alive, s.forward_blocked, s.reverse_blocked};
}

void FirmwareCore::flushMotion() {
  for (const MotionMessage& m : motion_->takeMessages())
    std::visit([this](const auto& message) { send(message); }, m);
}

// A started primitive replaces teleop: no teleop-expiry stop while it runs.
void FirmwareCore::afterStart() {
  flushMotion();
  if (!motion_->running())
    return;
  teleop_forward_ = teleop_yaw_cw_ = 0.0;
  last_teleop_s_.reset();
  teleop_was_active_ = false;
}

// MAV_CMD_IRGS_STOP: param7 0 stops everything (controlled stop, teleop ended); a primitive id
// stops only that primitive, so a retried stop of an old one cannot end a newer one.
std::uint8_t FirmwareCore::stopCommand(const mav::CommandLong& command) {
  const float id = command.param7;
  if (!std::isfinite(id) || id < 0.0f || id > 65535.0f || id != std::floor(id))
    return result(mav::MavResult::kDenied);
  if (id > 0.0f) {
    motion_->stop(static_cast<std::uint16_t>(id), motionNow());
    flushMotion();
    if (!motion_->running())
      motion_command_ = {};
    return result(mav::MavResult::kAccepted);
  }
  motion_->cancel(motionNow());
  flushMotion();
  motion_command_ = {};
  teleop_forward_ = teleop_yaw_cw_ = 0.0;
  last_teleop_s_.reset();
  sim_.setCommand({});  // controlled stop: decelerate at the profile's limits
  sendStatus(kSeverityInfo, "stop");
  return result(mav::MavResult::kAccepted);
}

// MAV_CMD_MISSION_START: param1 first item, param2 last item (0 or below the first: to the end).
std::uint8_t FirmwareCore::startMission(const mav::CommandLong& command) {
  const auto& points = mission_store_.waypoints();
  const double first_param = static_cast<double>(command.param1);
  const double last_param = static_cast<double>(command.param2);
  if (points.empty()) {
    sendStatus(kSeverityWarning, "MISSION_START: no mission uploaded");
    return result(mav::MavResult::kDenied);
  }
  if (mission_store_.uploading())
    return result(mav::MavResult::kTemporarilyRejected);
  if (!std::isfinite(first_param) || !std::isfinite(last_param) || first_param < 0.0 ||
      first_param >= static_cast<double>(points.size()))
    return result(mav::MavResult::kDenied);
  const auto first = static_cast<std::size_t>(first_param);
  std::size_t last = points.size() - 1;
  if (last_param > first_param && last_param < static_cast<double>(points.size()))
    last = static_cast<std::size_t>(last_param);
  MissionRequest request;
  request.waypoints.assign(points.begin() + static_cast<std::ptrdiff_t>(first),
                           points.begin() + static_cast<std::ptrdiff_t>(last) + 1);
  request.first_item = static_cast<std::uint16_t>(first);
  request.total_items = static_cast<std::uint16_t>(points.size());
  request.mission_id = mission_store_.missionId();
  const std::uint8_t answer = motion_->startMission(command, request, motionNow(), motionPermit());
  afterStart();
  return answer;
}

// ---- Telemetry ---------------------------------------------------------------------------------

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
  const bool behaviour = motion_->running();
  const bool mission = motion_->missionRunning();
  if (mission)
    hb.base_mode |= static_cast<std::uint8_t>(mav::MavModeFlag::kAutoEnabled);
  hb.custom_mode = estop_ ? 4u : mission ? 3u : behaviour ? 2u : teleop ? 1u : 0u;
  const VelocityCommand v = sim_.trueVelocity();
  const bool moving = v.linear_mps != 0.0 || v.angular_radps != 0.0;
  hb.system_status = static_cast<std::uint8_t>(estop_   ? mav::MavState::kEmergency
                                               : moving ? mav::MavState::kActive
                                                        : mav::MavState::kStandby);
  send(hb);
}

void FirmwareCore::sendLocalPosition(const TelemetrySample& sample) {
  // FLU -> NED (world x as north): rotation by pi about x (y and yaw change sign).
  const Pose2& p = sample.odometry_pose;
  const double v = sample.measured_velocity.linear_mps;
  mav::LocalPositionNed lp;
  lp.time_boot_ms = comms::bootMs(sample.time_s);
  lp.x = static_cast<float>(p.x);
  lp.y = static_cast<float>(-p.y);
  lp.vx = static_cast<float>(v * std::cos(p.theta));
  lp.vy = static_cast<float>(-v * std::sin(p.theta));
  send(lp);
}

void FirmwareCore::sendAttitude(const TelemetrySample& sample) {
  mav::Attitude att;
  att.time_boot_ms = comms::bootMs(sample.time_s);
  att.yaw = static_cast<float>(wrapAngle(-sample.odometry_pose.theta));
  att.yawspeed = static_cast<float>(-sample.measured_velocity.angular_radps);
  send(att);
}

void FirmwareCore::sendPose2d(const TelemetrySample& sample) {
  send(comms::pose2dMessage(sample));
}

void FirmwareCore::sendEncoderTicks(const TelemetrySample& sample) {
  send(comms::encoderTicksMessage(sample));
}

void FirmwareCore::sendMouseCounts(const TelemetrySample& sample) {
  if (!sample.mouse)
    return;
  send(comms::mouseCountsMessage(sample.time_s, *sample.mouse, mouse_worst_right_,
                                 mouse_worst_left_));
  mouse_worst_right_ = mouse_worst_left_ = MouseStatus::kTracking;
}

void FirmwareCore::sendCasterEncoders(const TelemetrySample& sample) {
  if (sample.casters)
    send(comms::casterEncodersMessage(sample.time_s, *sample.casters));
}

void FirmwareCore::sendOdometryMessage(const TelemetrySample& sample) {
  const Pose2& p = sample.odometry_pose;
  mav::Odometry od;
  od.time_usec = comms::bootUs(sample.time_s);
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

void FirmwareCore::sendDistanceSensors(const TelemetrySample& sample) {
  const auto& specs = sim_.profile().sonars;
  for (std::size_t i = 0; i < specs.size() && i < 256; ++i) {
    if (!fresh_sonar_[i])
      continue;
    send(comms::distanceSensorMessage(sample.time_s, i, specs[i], *fresh_sonar_[i]));
  }
  std::fill(fresh_sonar_.begin(), fresh_sonar_.end(), std::nullopt);
}

void FirmwareCore::sendSonarScan() {
  send(comms::sonarScanMessage(last_sonar_time_s_, last_sonar_,
                               static_cast<std::uint16_t>(scan_fired_ & 0xFFFFu)));
  scan_fired_ = 0;
}

void FirmwareCore::sendContact(const TelemetrySample& sample) {
  send(comms::contactMessage(sample, sim_.profile()));
}

// SCALED_IMU in the body FRD frame (x forward, y right, z down): a resting IMU reads -1 g on z;
// the yaw rate about z-down is minus our counter-clockwise omega. True motion plus white noise.
void FirmwareCore::sendScaledImu(const TelemetrySample& sample) {
  const VelocityCommand v = sim_.trueVelocity();
  const double to_mg = 1000.0 / kStandardGravity;
  auto noise = [&](double sigma) { return sigma * unit_normal_(imu_rng_); };
  mav::ScaledImu imu;
  imu.time_boot_ms = comms::bootMs(sample.time_s);
  imu.xacc = toInt16((accel_forward_mps2_ + noise(config_.accel_noise_mps2)) * to_mg);
  // Centripetal acceleration v * omega points left (FLU +y), i.e. FRD -y.
  imu.yacc = toInt16(-(v.linear_mps * v.angular_radps + noise(config_.accel_noise_mps2)) * to_mg);
  imu.zacc = toInt16(-(kStandardGravity + noise(config_.accel_noise_mps2)) * to_mg);
  imu.xgyro = toInt16(noise(config_.gyro_noise_radps) * 1000.0);
  imu.ygyro = toInt16(noise(config_.gyro_noise_radps) * 1000.0);
  // The yaw rate: the simulator's gyro model when it has one (its raw indicated rate, bias and
  // temperature included, as a real gyro reports it), else the true rate plus white noise. The
  // noise is drawn either way so the stream of the other axes does not depend on the gyro.
  const double yaw_noise = noise(config_.gyro_noise_radps);
  const double yaw_rate = sample.gyro ? sample.gyro->rate_radps : v.angular_radps + yaw_noise;
  imu.zgyro = toInt16(-yaw_rate * 1000.0);
  if (sample.gyro) {  // cdegC; 0 means "no temperature", so 0 C is sent as 0.01 C
    const std::int16_t cdeg = toInt16(sample.gyro->temperature_c * 100.0);
    imu.temperature = cdeg == 0 ? std::int16_t{1} : cdeg;
  }
  send(imu);
}

// SYS_STATUS: sensors present/healthy, the virtual battery and the link's receive errors
// (frames lost or corrupted on the way to the robot, as the decoder counted them).
void FirmwareCore::sendSysStatus() {
  mav::SysStatus st;
  std::uint32_t present = kSensorGyro | kSensorAccel | kSensorMotorOutputs | kSensorBattery;
  if (!sim_.profile().sonars.empty() || !sim_.profile().proximity.empty())
    present |= kSensorProximity;
  std::uint32_t health = present;
  if (estop_)
    health &= ~kSensorMotorOutputs;  // motors latched off
  const double remaining = batteryRemaining();
  if (remaining < 0.1)
    health &= ~kSensorBattery;
  st.onboard_control_sensors_present = present;
  st.onboard_control_sensors_enabled = present;
  st.onboard_control_sensors_health = health;
  const double volts =
      config_.battery_empty_v + (config_.battery_full_v - config_.battery_empty_v) * remaining;
  st.voltage_battery = static_cast<std::uint16_t>(std::lround(volts * 1000.0));
  st.current_battery = toInt16(battery_current_a_ * 100.0);
  st.battery_remaining = static_cast<std::int8_t>(std::lround(remaining * 100.0));
  const mav::DecodeCounters& rx = decoder_.totals();
  const std::uint64_t errors = rx.bad_crc + rx.bad_length + rx.sequence_gaps + rx.bad_signature +
                               rx.replay_rejected + rx.unsigned_rejected;
  const std::uint64_t attempts = rx.frames + errors;
  st.drop_rate_comm = static_cast<std::uint16_t>(
      attempts == 0
          ? 0
          : std::llround(10000.0 * static_cast<double>(errors) / static_cast<double>(attempts)));
  st.errors_comm = static_cast<std::uint16_t>(std::min<std::uint64_t>(errors, 65535));
  send(st);
}

}  // namespace irgs::app
