#include "app/robot/firmware_motion.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <type_traits>

#include "app/robot/firmware_mission.hpp"
#include "comms/robot/motion_messages.hpp"
#include "comms/robot/telemetry_messages.hpp"
#include "core/motion/host_adapters.hpp"

namespace irgs::app {

namespace mav = comms::mavlink;

namespace {

constexpr std::uint8_t result(mav::MavResult r) {
  return static_cast<std::uint8_t>(r);
}

constexpr auto kMissionStart = static_cast<std::uint16_t>(mav::MavCmd::kMissionStart);

void capAt(double& value, double max) {
  if (value > max)  // NaN and negative values stay: the executor refuses them (kInvalid)
    value = max;
}

mav::IrgsBehaviourState finalState(motion::ReportKind kind, motion::Reason reason, bool mission) {
  switch (kind) {
    case motion::ReportKind::kDone:
      return mav::IrgsBehaviourState::kSucceeded;
    case motion::ReportKind::kWallLost:
    case motion::ReportKind::kFrontWall:
      // A stop condition the spec asked for; a mission has not reached its waypoints.
      return mission ? mav::IrgsBehaviourState::kFailed : mav::IrgsBehaviourState::kSucceeded;
    case motion::ReportKind::kCancelled:
      return mav::IrgsBehaviourState::kAborted;
    case motion::ReportKind::kFailed:
      return reason == motion::Reason::kSafety ? mav::IrgsBehaviourState::kAborted
                                               : mav::IrgsBehaviourState::kFailed;
    default:
      return mav::IrgsBehaviourState::kFailed;  // kRefused
  }
}

std::string statusLine(const std::string& text) {
  return text.substr(0, 50);  // STATUSTEXT carries 50 characters
}

}  // namespace

FirmwareMotion::FirmwareMotion(const RobotProfile& profile, double status_period_s)
    : executor_(motion::motionGeometryOf(profile)),
      max_speed_mps_(profile.limits.max_speed_mps),
      max_turn_rate_radps_(profile.limits.max_turn_rate_radps),
      status_period_s_(status_period_s) {
  setStatusPeriod(status_period_s);
  setLimits(max_speed_mps_, max_turn_rate_radps_);
}

void FirmwareMotion::setStatusPeriod(double status_period_s) {
  if (!(status_period_s > 0.0))
    throw std::invalid_argument("FirmwareMotion: the status period must be > 0");
  status_period_s_ = status_period_s;
}

void FirmwareMotion::setLimits(double max_speed_mps, double max_turn_rate_radps) {
  max_speed_mps_ = max_speed_mps;
  max_turn_rate_radps_ = max_turn_rate_radps;
  motion::MotionSettings s = executor_.settings();
  s.speed_mps = 0.5 * max_speed_mps;  // the robot's default: half of MAX_SPEED
  s.turn_rate_radps = 0.5 * max_turn_rate_radps;
  const motion::WallFollowConfig follow_defaults;
  s.follow.speed_mps = std::min(follow_defaults.speed_mps, max_speed_mps);
  s.follow.turn_rate_radps = std::min(follow_defaults.turn_rate_radps, max_turn_rate_radps);
  executor_.setSettings(s);
}

// ---- Starts ------------------------------------------------------------------------------------

std::optional<std::uint8_t> FirmwareMotion::repeatedAnswer(std::uint16_t id,
                                                           const mav::CommandLong* command) const {
  if (id != 0) {
    for (const Answer& a : answers_)
      if (a.id == id)
        return a.result;
    return std::nullopt;
  }
  if (command == nullptr || command->confirmation == 0 || !anonymous_)
    return std::nullopt;
  mav::CommandLong retry = *command;
  retry.confirmation = 0;
  return retry == *anonymous_ ? std::optional<std::uint8_t>(anonymous_result_) : std::nullopt;
}

void FirmwareMotion::remember(std::uint16_t id, std::uint8_t answer,
                              const mav::CommandLong* command) {
  answers_[answer_next_] = {id, answer};
  answer_next_ = (answer_next_ + 1) % kHistory;
  if (command != nullptr) {
    anonymous_ = *command;
    anonymous_->confirmation = 0;
    anonymous_result_ = answer;
  }
}

std::uint16_t FirmwareMotion::nextRobotId() {
  const std::uint16_t id = next_robot_id_;
  next_robot_id_ =
      next_robot_id_ == 0xFFFF ? kFirstRobotId : static_cast<std::uint16_t>(next_robot_id_ + 1);
  return id;
}

std::optional<std::uint8_t> FirmwareMotion::onCommand(const mav::CommandLong& command,
                                                      const motion::MotionInput& now,
                                                      const MotionPermit& permit) {
  const std::optional<comms::DecodedPrimitive> decoded = comms::decodePrimitiveCommand(command);
  if (!decoded)
    return std::nullopt;
  if (!decoded->id_valid) {
    say(static_cast<std::uint8_t>(mav::MavSeverity::kWarning), decoded->error);
    return result(mav::MavResult::kDenied);
  }
  const mav::CommandLong* anonymous = decoded->id == 0 ? &command : nullptr;
  if (const auto again = repeatedAnswer(decoded->id, anonymous)) {
    sendStatus(now.time_s);  // a retry: the state as it is, nothing restarted
    return again;
  }
  const std::uint16_t id = decoded->id != 0 ? decoded->id : nextRobotId();
  std::uint8_t answer = result(mav::MavResult::kDenied);
  if (decoded->primitive) {
    motion::Primitive p = *decoded->primitive;
    p.id = id;
    answer = begin(p, command.command, now, permit, std::nullopt);
  } else {
    refuse(id, decoded->kind, command.command, motion::Reason::kInvalid, now);
    say(static_cast<std::uint8_t>(mav::MavSeverity::kWarning),
        std::string(motion::toString(decoded->kind)) + ": " + decoded->error);
  }
  remember(id, answer, anonymous);
  return answer;
}

void FirmwareMotion::onWaypoints(const mav::IrgsWaypoints& message, const motion::MotionInput& now,
                                 const MotionPermit& permit) {
  const comms::DecodedPrimitive decoded = comms::decodeWaypoints(message);
  if (repeatedAnswer(decoded.id, nullptr)) {
    sendStatus(now.time_s);  // the ground station resends until it hears of this id
    return;
  }
  const std::uint16_t id = decoded.id != 0 ? decoded.id : nextRobotId();
  std::uint8_t answer = result(mav::MavResult::kDenied);
  if (decoded.primitive) {
    motion::Primitive p = *decoded.primitive;
    p.id = id;
    answer = begin(p, 0, now, permit, std::nullopt);
  } else {
    refuse(id, decoded.kind, 0, motion::Reason::kInvalid, now);
    say(static_cast<std::uint8_t>(mav::MavSeverity::kWarning), "IRGS_WAYPOINTS: " + decoded.error);
  }
  remember(id, answer, nullptr);
}

std::uint8_t FirmwareMotion::startMission(const mav::CommandLong& command,
                                          const MissionRequest& mission,
                                          const motion::MotionInput& now,
                                          const MotionPermit& permit) {
  if (const auto again = repeatedAnswer(0, &command)) {
    sendStatus(now.time_s);
    return *again;
  }
  MissionRun run;
  run.total_items = mission.total_items;
  run.mission_id = mission.mission_id;
  for (const MissionLeg& leg : missionLegs(now.odometry, mission.waypoints)) {
    run.points.push_back(leg.segment.to);
    run.last_item.push_back(static_cast<std::uint16_t>(leg.last_item + mission.first_item));
  }
  if (run.points.empty() && !mission.waypoints.empty()) {
    // Standing on the waypoints already: one leg of no length, reached at once.
    run.points.push_back(mission.waypoints.back());
    run.last_item.push_back(
        static_cast<std::uint16_t>(mission.first_item + mission.waypoints.size() - 1));
  }
  const std::string started = "mission started: " + std::to_string(mission.waypoints.size()) +
                              " waypoints, " + std::to_string(run.points.size()) + " legs";
  motion::Primitive first;
  first.id = nextRobotId();
  motion::SegmentsSpec spec;
  for (std::size_t i = 0; i < run.points.size() && i < motion::kMaxWaypoints; ++i)
    spec.append(run.points[i]);
  spec.stop_at_wall = true;  // never into a wall the sonars see (docs/protocol.md section 13)
  first.spec = spec;
  const std::uint16_t id = first.id;
  const std::uint8_t answer = begin(first, kMissionStart, now, permit, std::move(run));
  if (answer == result(mav::MavResult::kAccepted))
    say(static_cast<std::uint8_t>(mav::MavSeverity::kInfo), started);
  remember(id, answer, &command);
  return answer;
}

std::optional<std::uint8_t> FirmwareMotion::refusalResult(const motion::Primitive& primitive,
                                                          const MotionPermit& permit,
                                                          motion::Reason& reason) const {
  reason = motion::Reason::kSafety;
  if (permit.estop)
    return result(mav::MavResult::kDenied);
  if (!permit.gcs_alive)
    return result(mav::MavResult::kTemporarilyRejected);
  if (const auto* drive = std::get_if<motion::DriveSpec>(&primitive.spec)) {
    // Toward a pressed bumper: refused until it is released (docs/protocol.md section 7).
    if ((permit.forward_blocked && drive->distance_m > 0.0) ||
        (permit.reverse_blocked && drive->distance_m < 0.0)) {
      reason = motion::Reason::kBumped;
      return result(mav::MavResult::kTemporarilyRejected);
    }
  }
  return std::nullopt;
}

void FirmwareMotion::capSpeeds(motion::PrimitiveSpec& spec) const {
  std::visit(
      [this](auto& s) {
        using S = std::decay_t<decltype(s)>;
        if constexpr (std::is_same_v<S, motion::TurnSpec>)
          capAt(s.rate_radps, max_turn_rate_radps_);
        else
          capAt(s.speed_mps, max_speed_mps_);
      },
      spec);
}

std::uint8_t FirmwareMotion::begin(motion::Primitive primitive, std::uint16_t command,
                                   const motion::MotionInput& now, const MotionPermit& permit,
                                   std::optional<MissionRun> mission) {
  const motion::PrimitiveKind kind = motion::kindOf(primitive.spec);
  motion::Reason reason = motion::Reason::kNone;
  if (const auto refused = refusalResult(primitive, permit, reason)) {
    refuse(primitive.id, kind, command, reason, now);
    return *refused;
  }
  capSpeeds(primitive.spec);
  // The running primitive ends first, reported with its own state (a mission's item numbers).
  executor_.cancel(now);
  drain(now);
  mission_ = std::move(mission);
  current_ = {};
  current_.id = primitive.id;
  current_.kind = kind;
  current_.command = command;
  if (const auto* turn = std::get_if<motion::TurnSpec>(&primitive.spec)) {
    const double turn_rad =
        turn->absolute ? wrapAngle(turn->angle_rad - now.odometry.theta) : turn->angle_rad;
    current_.sign = turn_rad < 0.0 ? -1.0 : 1.0;  // the executor reports |angle turned|
  }
  const bool started = executor_.start(primitive, now);
  drain(now);
  if (started)
    return result(mav::MavResult::kAccepted);
  return executor_.status().reason == motion::Reason::kUnsupported
             ? result(mav::MavResult::kUnsupported)
             : result(mav::MavResult::kDenied);
}

void FirmwareMotion::refuse(std::uint16_t id, motion::PrimitiveKind kind, std::uint16_t command,
                            motion::Reason reason, const motion::MotionInput& now) {
  executor_.cancel(now);  // a start replaces the running primitive, refused or not
  drain(now);
  mission_.reset();
  current_ = {};
  current_.id = id;
  current_.kind = kind;
  current_.command = command;
  publish({.id = id,
           .kind = motion::ReportKind::kRefused,
           .reason = reason,
           .time_s = now.time_s,
           .pose = now.odometry},
          false);
}

// ---- Stops -------------------------------------------------------------------------------------

void FirmwareMotion::stop(std::uint16_t id, const motion::MotionInput& now) {
  if (running() && executor_.status().id == id) {
    cancel(now);
    return;
  }
  if (repeatedAnswer(id, nullptr))
    return;  // it ended already: a stale stop changes nothing
  // Not started yet (its start lost, a retry on the way): it never will be.
  remember(id, result(mav::MavResult::kDenied), nullptr);
  out_.push_back(comms::motionReportMessage({.id = id,
                                             .kind = motion::ReportKind::kCancelled,
                                             .time_s = now.time_s,
                                             .pose = now.odometry}));
}

void FirmwareMotion::cancel(const motion::MotionInput& now) {
  executor_.cancel(now);
  drain(now);
}

void FirmwareMotion::abort(motion::Reason reason, const motion::MotionInput& now) {
  executor_.abort(reason, now);
  drain(now);
}

// ---- Steps and reports --------------------------------------------------------------------------

VelocityCommand FirmwareMotion::step(const motion::MotionInput& input) {
  VelocityCommand c = executor_.step(input);
  drain(input);
  if (running()) {
    current_.distance = executor_.status().distance_m + (mission_ ? mission_->distance_done : 0.0);
    if (input.time_s + 1e-9 >= next_status_s_)
      sendStatus(input.time_s);
  }
  c.linear_mps = std::clamp(c.linear_mps, -max_speed_mps_, max_speed_mps_);
  c.angular_radps = std::clamp(c.angular_radps, -max_turn_rate_radps_, max_turn_rate_radps_);
  return c;
}

bool FirmwareMotion::startChunk(const motion::MotionInput& at) {
  MissionRun& m = *mission_;
  motion::SegmentsSpec spec;
  for (std::size_t i = m.chunk_start; i < m.points.size() && spec.count < motion::kMaxWaypoints;
       ++i)
    spec.append(m.points[i]);
  spec.stop_at_wall = true;
  return executor_.start({current_.id, spec}, at);
}

void FirmwareMotion::drain(const motion::MotionInput& at) {
  motion::MotionReport r;
  while (executor_.popReport(r)) {
    const bool of_mission = mission_.has_value() && r.id == current_.id;
    if (of_mission && !translateMission(r, at))
      continue;
    publish(r, of_mission);
    if (of_mission && motion::isFinal(r.kind))
      mission_.reset();
  }
}

bool FirmwareMotion::translateMission(motion::MotionReport& r, const motion::MotionInput& at) {
  MissionRun& m = *mission_;
  r.distance_m += m.distance_done;
  const std::size_t legs = m.points.size();
  const std::string where =
      " on leg " + std::to_string(m.legs_done + 1) + " of " + std::to_string(legs);
  const auto warning = static_cast<std::uint8_t>(mav::MavSeverity::kWarning);
  switch (r.kind) {
    case motion::ReportKind::kStarted:
      if (m.chunk_start > 0)
        return false;  // the next chunk of the same mission
      sendMissionCurrent(0);
      return true;
    case motion::ReportKind::kTurningPoint: {
      const std::size_t leg = m.chunk_start + static_cast<std::size_t>(std::max<int>(r.index, 0));
      const std::uint16_t item = m.last_item[std::min(leg, legs - 1)];
      for (int i = m.reported + 1; i <= static_cast<int>(item); ++i) {
        mav::MissionItemReached reached;
        reached.seq = static_cast<std::uint16_t>(i);
        out_.push_back(reached);
      }
      m.reported = std::max(m.reported, static_cast<int>(item));
      m.legs_done = leg + 1;
      if (leg + 1 < legs)
        sendMissionCurrent(leg + 1);
      r.index = static_cast<std::int16_t>(item);
      return true;
    }
    case motion::ReportKind::kDone:
      if (m.chunk_start + motion::kMaxWaypoints < legs) {
        m.distance_done = r.distance_m;
        m.chunk_start += motion::kMaxWaypoints;
        startChunk(at);
        return false;
      }
      say(static_cast<std::uint8_t>(mav::MavSeverity::kInfo), "mission complete");
      return true;
    case motion::ReportKind::kRefused:
      if (m.chunk_start > 0) {  // a later chunk cannot start: the mission fails
        r.kind = motion::ReportKind::kFailed;
        r.reason = motion::Reason::kInvalid;
      }
      return true;
    case motion::ReportKind::kFrontWall:
      say(warning, "mission stopped: wall ahead" + where);
      return true;
    case motion::ReportKind::kFailed:
      if (r.reason == motion::Reason::kNoProgress)
        say(warning, "mission stalled" + where);
      else if (r.reason != motion::Reason::kSafety)
        say(warning, std::string("mission failed: ") + motion::toString(r.reason));
      return true;
    default:
      return true;
  }
}

void FirmwareMotion::sendMissionCurrent(std::size_t leg) {
  const MissionRun& m = *mission_;
  mav::MissionCurrent current;
  current.seq = m.last_item[std::min(leg, m.last_item.size() - 1)];
  current.total = m.total_items;
  current.mission_id = m.mission_id;
  out_.push_back(current);
}

void FirmwareMotion::publish(const motion::MotionReport& r, bool of_mission) {
  out_.push_back(comms::motionReportMessage(r));
  if (r.id != current_.id)
    return;  // a report of a primitive no longer current
  current_.last = r.kind;
  current_.reason = r.reason;
  current_.distance = r.distance_m;
  if (r.kind == motion::ReportKind::kTurningPoint)
    current_.index = r.index;
  if (r.kind == motion::ReportKind::kStarted) {
    current_.state = mav::IrgsBehaviourState::kRunning;
  } else if (motion::isFinal(r.kind)) {
    current_.state = finalState(r.kind, r.reason, of_mission);
  } else {
    return;  // progress: the periodic status carries it
  }
  sendStatus(r.time_s);  // on every state change
  const auto warning = static_cast<std::uint8_t>(mav::MavSeverity::kWarning);
  const std::string what = motion::toString(current_.kind);
  if (r.kind == motion::ReportKind::kRefused)
    say(warning, what + " refused: " + motion::toString(r.reason));
  else if (!of_mission && r.kind == motion::ReportKind::kFailed &&
           r.reason != motion::Reason::kSafety)
    say(warning, what + " failed: " + motion::toString(r.reason));
}

void FirmwareMotion::requestStatus(double time_s) {
  sendStatus(time_s);
}

void FirmwareMotion::sendStatus(double time_s) {
  mav::IrgsBehaviourStatus s;
  s.time_boot_ms = comms::bootMs(time_s);
  s.command = current_.command;
  s.state = static_cast<std::uint8_t>(current_.state);
  s.progress = static_cast<float>(current_.sign * current_.distance);
  s.id = current_.id;
  s.index = current_.index;
  s.kind = static_cast<std::uint8_t>(current_.kind);
  s.report = static_cast<std::uint8_t>(current_.last);
  s.reason = static_cast<std::uint8_t>(current_.reason);
  out_.push_back(s);
  next_status_s_ = time_s + status_period_s_;
}

void FirmwareMotion::say(std::uint8_t severity, const std::string& text) {
  mav::Statustext m;
  m.severity = severity;
  mav::setString(m.text, statusLine(text));
  out_.push_back(m);
}

std::vector<MotionMessage> FirmwareMotion::takeMessages() {
  std::vector<MotionMessage> out;
  out.swap(out_);
  return out;
}

}  // namespace irgs::app
