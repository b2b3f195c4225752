#include "core/mission/travel_mission.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <utility>

namespace irgs {
namespace {

std::string formatPoint(const Vec2& p) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "(%.2f, %.2f)", p.x(), p.y());
  return buffer;
}

}  // namespace

TravelMission::TravelMission(std::vector<Vec2> points, TravelMissionConfig config)
    : points_(std::move(points)), config_(config) {
  for (const Vec2& p : points_)
    if (!std::isfinite(p.x()) || !std::isfinite(p.y()))
      throw std::invalid_argument("TravelMission: a turning point is not finite");
  if (!(config_.speed_mps > 0.0) || !std::isfinite(config_.speed_mps) ||
      !(config_.turn_quantum_rad >= 0.0) || !std::isfinite(config_.turn_quantum_rad) ||
      !(config_.stop_distance_m >= 0.0) || !std::isfinite(config_.stop_distance_m))
    throw std::invalid_argument("TravelMission: speed > 0, quantum and stop distance >= 0");
  for (std::size_t i = 1; i < points_.size(); ++i)
    total_m_ += (points_[i] - points_[i - 1]).norm();
  if (points_.size() < 2)
    finish(false, "nothing to travel");
}

void TravelMission::finish(bool failed, std::string message) {
  finished_ = true;
  failed_ = failed;
  message_ = std::move(message);
  if (active_id_ != 0)
    request_ = CancelPrimitive{};
  active_id_ = 0;
}

void TravelMission::sendChunk() {
  motion::SegmentsSpec spec;
  spec.speed_mps = config_.speed_mps;
  spec.quantum_rad = config_.turn_quantum_rad;
  spec.stop_at_wall = config_.stop_distance_m > 0.0;
  spec.clearance_m = config_.stop_distance_m;
  chunk_from_ = reached_;
  for (std::size_t i = reached_ + 1; i < points_.size() && spec.append(points_[i]); ++i) {
  }
  active_id_ = next_id_++;
  request_ = StartPrimitive{{active_id_, spec}};
}

void TravelMission::onSample(const TelemetrySample& sample) {
  if (finished_ || started_)
    return;
  (void)sample;
  started_ = true;
  sendChunk();
}

void TravelMission::onReport(const motion::MotionReport& report) {
  using motion::ReportKind;
  if (finished_ || report.id != active_id_)
    return;
  if (report.kind == ReportKind::kTurningPoint) {
    reached_ = chunk_from_ + static_cast<std::size_t>(report.index) + 1;
    done_m_ = 0.0;
    for (std::size_t i = 1; i <= reached_; ++i)
      done_m_ += (points_[i] - points_[i - 1]).norm();
    arrivals_.push_back(report.pose.position());
    if (reached_ + 1 < points_.size())
      message_ = "arrived at turning point " + std::to_string(reached_) + "/" +
                 std::to_string(points_.size() - 2) + " " + formatPoint(points_[reached_]);
    return;
  }
  if (!motion::isFinal(report.kind))
    return;
  active_id_ = 0;
  if (report.kind == ReportKind::kDone) {
    if (reached_ + 1 >= points_.size())
      return finish(false, "arrived at the goal " + formatPoint(points_.back()));
    return sendChunk();  // the next chunk of a long path
  }
  const std::string where =
      " at " + formatPoint(report.pose.position()) + " on leg " + std::to_string(reached_ + 1);
  switch (report.kind) {
    case ReportKind::kFrontWall:
      return finish(true, "blocked ahead" + where);
    case ReportKind::kFailed:
      return finish(true, std::string(motion::toString(report.reason)) + where);
    default:
      return finish(true, std::string("travel ") + motion::toString(report.kind) + where);
  }
}

std::optional<MissionRequest> TravelMission::takeRequest() {
  return std::exchange(request_, std::nullopt);
}

BehaviourStatus TravelMission::status() const {
  BehaviourStatus s;
  s.finished = finished_;
  s.failed = failed_;
  s.message = message_;
  const std::size_t legs = points_.size() > 1 ? points_.size() - 1 : 0;
  s.phase = finished_ ? (failed_ ? "failed" : "arrived")
                      : "leg " + std::to_string(std::min(reached_ + 1, legs)) + "/" +
                            std::to_string(legs);
  if (finished_ && !failed_)
    s.progress = 1.0;
  else if (total_m_ > 1e-9)
    s.progress = std::clamp(done_m_ / total_m_, 0.0, 1.0);  // by turning points reached
  return s;
}

}  // namespace irgs
