#include "core/motion/motion_executor.hpp"

#include <cmath>

namespace irgs::motion {
namespace {

// Sonar readings older than this no longer count for the forward stop of drive and segments.
constexpr double kStopSonarRange_m = 4.0;

template <class... Ts>
struct Overloaded : Ts... {
  using Ts::operator()...;
};
template <class... Ts>
Overloaded(Ts...) -> Overloaded<Ts...>;

}  // namespace

MotionExecutor::MotionExecutor(const MotionGeometry& geometry, const MotionSettings& settings)
    : geometry_(geometry), settings_(settings), sonar_(geometry_, kStopSonarRange_m) {}

void MotionExecutor::push(ReportKind kind, Reason reason, std::int16_t index,
                          const MotionInput& at) {
  MotionReport r;
  r.id = status_.id;
  r.kind = kind;
  r.reason = reason;
  r.time_s = at.time_s;
  r.pose = at.odometry;
  r.distance_m = driven();
  r.index = index;
  if (report_count_ == kReportCapacity) {
    // Full (nobody took them): the oldest goes. Final reports are what matter most and are
    // the newest.
    report_head_ = (report_head_ + 1) % kReportCapacity;
    --report_count_;
    ++dropped_reports_;
  }
  reports_[(report_head_ + report_count_) % kReportCapacity] = r;
  ++report_count_;
  status_.last = kind;
  status_.reason = reason;
}

bool MotionExecutor::popReport(MotionReport& report) {
  if (report_count_ == 0)
    return false;
  report = reports_[report_head_];
  report_head_ = (report_head_ + 1) % kReportCapacity;
  --report_count_;
  return true;
}

double MotionExecutor::driven() const {
  return std::visit(Overloaded{[](const std::monostate&) { return 0.0; },
                               [](const TurnPrimitive& p) { return std::abs(p.turned_rad()); },
                               [](const auto& p) { return p.driven_m(); }},
                    active_);
}

void MotionExecutor::end(ReportKind kind, Reason reason, const MotionInput& at) {
  if (!status_.running)
    return;
  status_.distance_m = driven();
  push(kind, reason, -1, at);
  status_.running = false;
  active_ = std::monostate{};
}

bool MotionExecutor::start(const Primitive& primitive, const MotionInput& now) {
  end(ReportKind::kCancelled, Reason::kNone, now);
  status_ = {};
  status_.id = primitive.id;
  status_.kind = kindOf(primitive.spec);
  bool ok = primitive.id != 0;
  Reason refusal = Reason::kInvalid;
  if (ok) {
    ok = std::visit(
        Overloaded{
            [&](const TurnSpec& s) {
              return active_.emplace<TurnPrimitive>().start(s, now, settings_);
            },
            [&](const DriveSpec& s) {
              return active_.emplace<DrivePrimitive>().start(s, now, settings_, geometry_);
            },
            [&](const FollowWallSpec& s) {
              const bool started =
                  active_.emplace<FollowWallPrimitive>().start(s, now, settings_, geometry_);
              if (!started && std::isfinite(s.distance_m) && s.distance_m > 0.0 &&
                  !findSonarRoles(geometry_).canFollow(s.wall_on_left))
                refusal = Reason::kNoSensors;
              return started;
            },
            [&](const SegmentsSpec& s) {
              return active_.emplace<SegmentsPrimitive>().start(s, now, settings_, geometry_);
            },
            [&](const FollowPathSpec& s) {
              return active_.emplace<FollowPathPrimitive>().start(s, now, settings_, geometry_);
            }},
        primitive.spec);
  }
  if (!ok) {
    active_ = std::monostate{};
    push(ReportKind::kRefused, refusal, -1, now);
    return false;
  }
  sonar_.forgetBefore(now.time_s);
  status_.running = true;
  push(ReportKind::kStarted, Reason::kNone, -1, now);
  return true;
}

void MotionExecutor::cancel(const MotionInput& now) {
  end(ReportKind::kCancelled, Reason::kNone, now);
}

void MotionExecutor::abort(Reason reason, const MotionInput& now) {
  end(ReportKind::kFailed, reason, now);
}

const WallFollowControl* MotionExecutor::wallFollower() const {
  const auto* follow = std::get_if<FollowWallPrimitive>(&active_);
  return follow && follow->control() ? &*follow->control() : nullptr;
}

VelocityCommand MotionExecutor::step(const MotionInput& input) {
  sonar_.update(input);
  heading_setpoint_.reset();
  distance_setpoint_.reset();
  if (!status_.running)
    return {};
  const Pose2& p = input.odometry;
  if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.theta)) {
    end(ReportKind::kFailed, Reason::kInvalid, input);
    return {};
  }
  const StepOutcome out =
      std::visit(Overloaded{[](std::monostate&) { return StepOutcome{}; },
                            [&](TurnPrimitive& t) { return t.step(input); },
                            [&](DrivePrimitive& d) { return d.step(input, sonar_); },
                            [&](FollowWallPrimitive& f) { return f.step(input); },
                            [&](SegmentsPrimitive& s) { return s.step(input, sonar_); },
                            [&](FollowPathPrimitive& f) { return f.step(input); }},
                 active_);
  status_.distance_m = driven();
  for (std::size_t i = 0; i < out.note_count; ++i) {
    const Note& n = out.notes[i];
    if (out.finished && i + 1 == out.note_count) {
      end(n.kind, n.reason, input);
    } else {
      push(n.kind, n.reason, n.index, input);
    }
  }
  if (out.finished)
    return {};
  heading_setpoint_ = out.heading_rad;
  distance_setpoint_ = out.distance;
  return out.command;
}

}  // namespace irgs::motion
