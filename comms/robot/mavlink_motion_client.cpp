#include "comms/robot/mavlink_motion_client.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "comms/robot/motion_messages.hpp"

namespace irgs::comms {

namespace mav = mavlink;

namespace {

// A robot clock more than this behind the newest time known: the robot restarted.
constexpr double kRestartJump_s = 1.0;

bool isWaypointKind(motion::PrimitiveKind kind) {
  return kind == motion::PrimitiveKind::kSegments || kind == motion::PrimitiveKind::kFollowPath;
}

// The reason a refusal's MAV_RESULT implies, when its kRefused report was lost as well.
motion::Reason reasonOfResult(std::optional<std::uint8_t> result) {
  switch (static_cast<mav::MavResult>(result.value_or(0xFF))) {
    case mav::MavResult::kDenied:
      return motion::Reason::kInvalid;
    case mav::MavResult::kTemporarilyRejected:
      return motion::Reason::kSafety;
    case mav::MavResult::kUnsupported:
      return motion::Reason::kUnsupported;
    default:
      return motion::Reason::kNone;
  }
}

// The final report a status's end state implies when its report field is not a final one.
motion::ReportKind kindOfState(std::uint8_t state) {
  switch (static_cast<mav::IrgsBehaviourState>(state)) {
    case mav::IrgsBehaviourState::kSucceeded:
      return motion::ReportKind::kDone;
    case mav::IrgsBehaviourState::kAborted:
      return motion::ReportKind::kCancelled;
    default:
      return motion::ReportKind::kFailed;
  }
}

}  // namespace

MavlinkMotionClient::MavlinkMotionClient(MotionClientConfig config) : config_(config) {
  if (!(config_.retry_s > 0.0) || !(config_.status_timeout_s > 0.0) ||
      !(config_.report_hold_s >= 0.0) || config_.max_attempts < 1 || config_.max_tracked < 1)
    throw std::invalid_argument("MotionClientConfig: periods must be > 0, attempts >= 1");
}

MavlinkMotionClient::Tracked* MavlinkMotionClient::find(std::uint16_t id) {
  for (Tracked& t : tracked_)
    if (t.id == id)
      return &t;
  return nullptr;
}

MavlinkMotionClient::Tracked& MavlinkMotionClient::track(const motion::Primitive& primitive,
                                                         double now_s) {
  // An id used again: the caller is done with the old primitive (or it never got an answer).
  std::erase_if(tracked_, [&](const Tracked& t) { return t.id == primitive.id; });
  while (tracked_.size() >= config_.max_tracked) {
    Tracked& oldest = tracked_.front();
    if (!oldest.final)
      deliver(oldest, motion::ReportKind::kCancelled, motion::Reason::kNone, robot_time_s_, now_s);
    tracked_.pop_front();
  }
  Tracked t;
  t.id = primitive.id;
  t.kind = motion::kindOf(primitive.spec);
  t.order = next_order_++;
  t.last_heard_s = now_s;
  tracked_.push_back(t);
  return tracked_.back();
}

void MavlinkMotionClient::start(const motion::Primitive& primitive, double now_s) {
  const EncodedPrimitive encoded = encodePrimitive(primitive, target_system_);
  Tracked& t = track(primitive, now_s);
  if (primitive.id == 0 || !encoded.error.empty()) {
    deliver(t, motion::ReportKind::kRefused, motion::Reason::kInvalid, robot_time_s_, now_s);
    return;
  }
  if (encoded.command) {
    out_.commands.push_back({primitive.id, *encoded.command});
    return;
  }
  t.resend = *encoded.waypoints;
  t.attempts = 1;
  t.next_send_s = now_s + config_.retry_s;
  out_.waypoints.push_back(*encoded.waypoints);
}

void MavlinkMotionClient::cancel(double now_s) {
  Tracked* newest = nullptr;
  for (Tracked& t : tracked_)
    if (!t.final && (newest == nullptr || t.order > newest->order))
      newest = &t;
  if (newest == nullptr)
    return;
  newest->resend.reset();  // a waypoint list not yet started is not sent again
  newest->last_heard_s = now_s;
  out_.commands.push_back({newest->id, stopPrimitiveCommand(newest->id, target_system_)});
}

void MavlinkMotionClient::onFrame(const mav::Frame& frame, double now_s) {
  if (const auto report = frame.as<mav::IrgsMotionReport>())
    onReport(*report, now_s);
  else if (const auto status = frame.as<mav::IrgsBehaviourStatus>())
    onStatus(*status, now_s);
}

void MavlinkMotionClient::noteRobotTime(double robot_time_s) {
  if (robot_time_s > robot_time_s_ || robot_time_s < robot_time_s_ - kRestartJump_s)
    robot_time_s_ = robot_time_s;
}

void MavlinkMotionClient::onSample(double robot_time_s, const Pose2& odometry) {
  noteRobotTime(robot_time_s);
  pose_ = odometry;
}

void MavlinkMotionClient::heard(Tracked& t, double now_s) {
  t.heard = true;
  t.resend.reset();
  t.last_heard_s = now_s;
}

void MavlinkMotionClient::endOlder(const Tracked* current, double robot_time_s, double now_s) {
  // The robot runs one primitive at a time: once `current` (or a foreign one, nullptr) is the
  // robot's, every other primitive the robot confirmed has ended, and every one of ours sent
  // before `current` was replaced before the robot said anything of it.
  for (Tracked& t : tracked_) {
    if (t.final || &t == current)
      continue;
    if (t.heard || (current != nullptr && t.order < current->order))
      deliver(t, motion::ReportKind::kCancelled, motion::Reason::kNone, robot_time_s, now_s);
  }
}

void MavlinkMotionClient::onReport(const mav::IrgsMotionReport& message, double now_s) {
  const std::optional<motion::MotionReport> report = motionReportFrom(message);
  if (!report)
    return;
  noteRobotTime(report->time_s);
  Tracked* t = find(report->id);
  // A start or a refusal replaces what the robot ran (other reports do not: a stop of a
  // primitive the robot never started is answered kCancelled while another runs on).
  if (report->kind == motion::ReportKind::kStarted || report->kind == motion::ReportKind::kRefused)
    endOlder(t, report->time_s, now_s);
  if (t == nullptr || t->final)
    return;  // not ours, or ended here already (made up from a status, a result, link loss)
  heard(*t, now_s);
  switch (report->kind) {
    case motion::ReportKind::kStarted:
      if (!t->started)
        deliver(*t, *report, now_s);
      return;
    case motion::ReportKind::kRefused:
      deliver(*t, *report, now_s);
      return;
    case motion::ReportKind::kTurningPoint:
      if (report->index <= t->last_index)
        return;  // made up from a status before this frame arrived
      break;
    default:
      break;
  }
  if (!t->started) {
    motion::MotionReport started = *report;
    started.kind = motion::ReportKind::kStarted;
    started.reason = motion::Reason::kNone;
    started.index = -1;
    started.distance_m = 0.0;
    deliver(*t, started, now_s);
  }
  deliver(*t, *report, now_s);
}

void MavlinkMotionClient::onStatus(const mav::IrgsBehaviourStatus& status, double now_s) {
  if (status.id == 0)
    return;  // nothing ran yet, or a firmware that does not name its primitives
  const double time_s = static_cast<double>(status.time_boot_ms) * 1e-3;
  noteRobotTime(time_s);
  Tracked* t = find(status.id);
  // The status names the robot's current (or last) primitive: no other one runs.
  endOlder(t, time_s, now_s);
  if (t == nullptr)
    return;
  const bool running = status.state == static_cast<std::uint8_t>(mav::IrgsBehaviourState::kRunning);
  if (t->final) {
    if (running)
      stopOnRobot(*t, now_s);  // ended here (link loss) but still running there
    return;
  }
  heard(*t, now_s);
  const std::optional<motion::ReportKind> last = reportKindFrom(status.report);
  const motion::Reason reason = reasonFrom(status.reason).value_or(motion::Reason::kNone);
  const double distance = std::abs(static_cast<double>(status.progress));
  if (!running && last == motion::ReportKind::kRefused) {
    deliver(*t, motion::ReportKind::kRefused, reason, time_s, now_s);
    return;
  }
  if (status.state == static_cast<std::uint8_t>(mav::IrgsBehaviourState::kIdle))
    return;
  ensureStarted(*t, time_s, now_s);
  if (isWaypointKind(t->kind)) {
    for (int i = t->last_index + 1; i <= status.index; ++i)
      deliver(*t, motion::ReportKind::kTurningPoint, motion::Reason::kNone, time_s, now_s,
              static_cast<std::int16_t>(i), distance);
  }
  if (running)
    return;
  const motion::ReportKind final =
      last && motion::isFinal(*last) ? *last : kindOfState(status.state);
  deliver(*t, final, reason, time_s, now_s, -1, distance);
}

void MavlinkMotionClient::onCommandResult(std::uint16_t primitive_id, const CommandResult& result,
                                          double now_s) {
  Tracked* t = primitive_id != 0 ? find(primitive_id) : nullptr;
  if (t == nullptr || t->final)
    return;
  if (result.command == static_cast<std::uint16_t>(mav::MavCmd::kIrgsStop)) {
    // The robot sends the primitive's final report before acknowledging the stop: it was lost.
    if (result.outcome == CommandOutcome::kAccepted)
      deliver(*t, motion::ReportKind::kCancelled, motion::Reason::kNone, robot_time_s_, now_s);
    return;
  }
  switch (result.outcome) {
    case CommandOutcome::kAccepted:
      heard(*t, now_s);
      ensureStarted(*t, robot_time_s_, now_s);
      break;
    case CommandOutcome::kRejected:
      deliver(*t, t->started ? motion::ReportKind::kFailed : motion::ReportKind::kRefused,
              reasonOfResult(result.mav_result), robot_time_s_, now_s);
      break;
    case CommandOutcome::kTimedOut:
      if (!t->heard)  // every transmission or every answer lost
        deliver(*t, motion::ReportKind::kRefused, motion::Reason::kNoAnswer, robot_time_s_, now_s);
      break;
    case CommandOutcome::kCancelled:
      if (!t->heard)  // superseded before any answer, or the link closed
        deliver(*t, motion::ReportKind::kCancelled, motion::Reason::kNone, robot_time_s_, now_s);
      break;
  }
}

void MavlinkMotionClient::onLinkLost(double now_s) {
  for (Tracked& t : tracked_) {
    if (t.final)
      continue;
    deliver(t, motion::ReportKind::kFailed, motion::Reason::kSafety, robot_time_s_, now_s);
    t.lost_with_link = true;
  }
}

void MavlinkMotionClient::tick(double now_s) {
  bool quiet = false;
  for (Tracked& t : tracked_) {
    if (t.final)
      continue;
    if (t.resend && now_s >= t.next_send_s) {
      if (t.attempts < config_.max_attempts) {
        out_.waypoints.push_back(*t.resend);
        ++t.attempts;
        t.next_send_s = now_s + config_.retry_s;
      } else {
        t.resend.reset();
        deliver(t, motion::ReportKind::kRefused, motion::Reason::kNone, robot_time_s_, now_s);
        continue;
      }
    }
    quiet = quiet || (t.heard && now_s - t.last_heard_s >= config_.status_timeout_s);
  }
  if (quiet && now_s >= next_status_request_s_) {
    mav::CommandLong request;
    request.target_system = target_system_;
    request.command = static_cast<std::uint16_t>(mav::MavCmd::kRequestMessage);
    request.param1 = static_cast<float>(mav::IrgsBehaviourStatus::kId);
    out_.commands.push_back({0, request});
    next_status_request_s_ = now_s + config_.status_timeout_s;
  }
}

void MavlinkMotionClient::stopOnRobot(Tracked& t, double now_s) {
  if (now_s < t.next_stop_s)
    return;
  t.next_stop_s = now_s + config_.status_timeout_s;
  out_.commands.push_back({t.id, stopPrimitiveCommand(t.id, target_system_)});
}

void MavlinkMotionClient::ensureStarted(Tracked& t, double robot_time_s, double now_s) {
  if (!t.started && !t.final)
    deliver(t, motion::ReportKind::kStarted, motion::Reason::kNone, robot_time_s, now_s);
}

void MavlinkMotionClient::deliver(Tracked& t, motion::ReportKind kind, motion::Reason reason,
                                  double robot_time_s, double now_s, std::int16_t index,
                                  double distance_m) {
  deliver(t,
          {.id = t.id,
           .kind = kind,
           .reason = reason,
           .time_s = robot_time_s,
           .pose = pose_,
           .distance_m = distance_m,
           .index = index},
          now_s);
}

void MavlinkMotionClient::deliver(Tracked& t, const motion::MotionReport& report, double now_s) {
  if (report.kind == motion::ReportKind::kStarted)
    t.started = true;
  if (report.kind == motion::ReportKind::kTurningPoint)
    t.last_index = std::max(t.last_index, report.index);
  if (motion::isFinal(report.kind)) {
    t.final = true;
    t.resend.reset();
  }
  reports_.push_back({report, now_s});
}

MotionClientOutput MavlinkMotionClient::takeOutput() {
  MotionClientOutput out;
  std::swap(out, out_);
  return out;
}

std::vector<motion::MotionReport> MavlinkMotionClient::takeReports(double delivered_until_s,
                                                                   double now_s) {
  std::vector<motion::MotionReport> out;
  while (!reports_.empty()) {
    const Queued& q = reports_.front();
    if (q.report.time_s > delivered_until_s + 1e-9 && now_s - q.queued_s < config_.report_hold_s)
      break;  // its samples are still on the way: keep the order
    out.push_back(q.report);
    reports_.pop_front();
  }
  return out;
}

}  // namespace irgs::comms
