#include "app/robot/firmware_mission.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace irgs::app {

namespace mav = comms::mavlink;

namespace {

constexpr double kLocalScale = 1e4;  // MISSION_ITEM_INT local x/y: metres * 1e4

std::uint8_t missionResult(mav::MavMissionResult r) {
  return static_cast<std::uint8_t>(r);
}

// A waypoint item in our world frame, or why it cannot be one.
std::optional<Vec2> itemPosition(const mav::MissionItemInt& m, mav::MavMissionResult& error) {
  if (m.command != static_cast<std::uint16_t>(mav::MavCmd::kNavWaypoint)) {
    error = mav::MavMissionResult::kUnsupported;
    return std::nullopt;
  }
  const double x = static_cast<double>(m.x) / kLocalScale;
  const double y = static_cast<double>(m.y) / kLocalScale;
  if (m.frame == static_cast<std::uint8_t>(mav::MavFrame::kLocalNed))
    return Vec2(x, -y);  // NED with our x as north: east = -y (docs/protocol.md section 3)
  if (m.frame == static_cast<std::uint8_t>(mav::MavFrame::kLocalFlu))
    return Vec2(x, y);
  error = mav::MavMissionResult::kUnsupportedFrame;
  return std::nullopt;
}

std::int32_t toLocalInt(double metres) {
  const double scaled = std::round(metres * kLocalScale);
  return static_cast<std::int32_t>(
      std::clamp(scaled, static_cast<double>(std::numeric_limits<std::int32_t>::min()),
                 static_cast<double>(std::numeric_limits<std::int32_t>::max())));
}

}  // namespace

MissionStore::MissionStore(std::uint8_t system_id, std::uint8_t component_id)
    : system_id_(system_id), component_id_(component_id) {}

mav::MissionRequestInt MissionStore::requestFor(const Upload& u) const {
  mav::MissionRequestInt r;
  r.target_system = u.gcs_system;
  r.target_component = u.gcs_component;
  r.seq = u.next;
  r.mission_type = static_cast<std::uint8_t>(mav::MavMissionType::kMission);
  return r;
}

mav::MissionAck MissionStore::ack(std::uint8_t gcs_system, std::uint8_t gcs_component,
                                  mav::MavMissionResult result, std::uint8_t mission_type) const {
  mav::MissionAck a;
  a.target_system = gcs_system;
  a.target_component = gcs_component;
  a.type = missionResult(result);
  a.mission_type = mission_type;
  a.opaque_id = mission_id_;
  return a;
}

MissionReply MissionStore::onCount(const mav::MissionCount& m, std::uint8_t gcs_system,
                                   std::uint8_t gcs_component, double now_s) {
  MissionReply reply;
  if (m.mission_type != static_cast<std::uint8_t>(mav::MavMissionType::kMission)) {
    // Fences and rally points mean nothing indoors.
    reply.ack = ack(gcs_system, gcs_component, mav::MavMissionResult::kUnsupported, m.mission_type);
    return reply;
  }
  if (m.count > kMaxMissionItems) {
    reply.ack = ack(gcs_system, gcs_component, mav::MavMissionResult::kNoSpace);
    reply.status = "mission of " + std::to_string(m.count) + " items refused (max " +
                   std::to_string(kMaxMissionItems) + ")";
    reply.warning = true;
    return reply;
  }
  if (m.count == 0) {  // an empty upload clears the mission
    upload_.reset();
    waypoints_.clear();
    ++mission_id_;
    reply.ack = ack(gcs_system, gcs_component, mav::MavMissionResult::kAccepted);
    return reply;
  }
  // A new MISSION_COUNT restarts any upload in progress (the GCS gave up on it).
  Upload u;
  u.count = m.count;
  u.gcs_system = gcs_system;
  u.gcs_component = gcs_component;
  u.requested_at_s = now_s;
  u.points.reserve(m.count);
  upload_ = u;
  reply.request = requestFor(*upload_);
  return reply;
}

MissionReply MissionStore::onItem(const mav::MissionItemInt& m, std::uint8_t gcs_system,
                                  std::uint8_t gcs_component, double now_s) {
  MissionReply reply;
  if (!upload_ || gcs_system != upload_->gcs_system)
    return reply;  // no upload from this sender: ignore (the spec's rule for stray items)
  if (m.mission_type != static_cast<std::uint8_t>(mav::MavMissionType::kMission))
    return reply;
  if (m.seq != upload_->next) {
    // A duplicate of an item we already have (our request crossed a resend) or one ahead of
    // the sequence: ask again for the one we need.
    reply.request = requestFor(*upload_);
    upload_->requested_at_s = now_s;
    return reply;
  }
  mav::MavMissionResult error = mav::MavMissionResult::kAccepted;
  const std::optional<Vec2> p = itemPosition(m, error);
  if (!p) {
    reply.ack = ack(gcs_system, gcs_component, error);
    // STATUSTEXT carries 50 characters: keep it short.
    reply.status = "mission item " + std::to_string(m.seq) +
                   (error == mav::MavMissionResult::kUnsupportedFrame ? ": frame not LOCAL_NED/FLU"
                                                                      : ": not a NAV_WAYPOINT");
    reply.warning = true;
    upload_.reset();  // the stored mission stays as it was
    return reply;
  }
  upload_->points.push_back(*p);
  ++upload_->next;
  upload_->retries = 0;
  upload_->requested_at_s = now_s;
  if (upload_->next < upload_->count) {
    reply.request = requestFor(*upload_);
    return reply;
  }
  waypoints_ = std::move(upload_->points);
  upload_.reset();
  ++mission_id_;
  reply.ack = ack(gcs_system, gcs_component, mav::MavMissionResult::kAccepted);
  reply.status = "mission of " + std::to_string(waypoints_.size()) + " waypoints received";
  return reply;
}

MissionReply MissionStore::poll(double now_s) {
  MissionReply reply;
  if (!upload_ || now_s - upload_->requested_at_s < kItemTimeout_s)
    return reply;
  if (upload_->retries >= kMaxRetries) {
    reply.ack = ack(upload_->gcs_system, upload_->gcs_component,
                    mav::MavMissionResult::kOperationCancelled);
    reply.status = "mission upload timed out waiting for item " + std::to_string(upload_->next);
    reply.warning = true;
    upload_.reset();
    return reply;
  }
  ++upload_->retries;
  upload_->requested_at_s = now_s;
  reply.request = requestFor(*upload_);
  return reply;
}

MissionReply MissionStore::onRequestList(const mav::MissionRequestList& m, std::uint8_t gcs_system,
                                         std::uint8_t gcs_component) {
  MissionReply reply;
  mav::MissionCount c;
  c.target_system = gcs_system;
  c.target_component = gcs_component;
  c.mission_type = m.mission_type;
  c.count = m.mission_type == static_cast<std::uint8_t>(mav::MavMissionType::kMission)
                ? static_cast<std::uint16_t>(waypoints_.size())
                : 0;  // no fences, no rally points
  c.opaque_id = mission_id_;
  reply.count = c;
  return reply;
}

MissionReply MissionStore::onRequest(const mav::MissionRequestInt& m, std::uint8_t gcs_system,
                                     std::uint8_t gcs_component) {
  MissionReply reply;
  if (m.mission_type != static_cast<std::uint8_t>(mav::MavMissionType::kMission) ||
      m.seq >= waypoints_.size()) {
    reply.ack =
        ack(gcs_system, gcs_component, mav::MavMissionResult::kInvalidSequence, m.mission_type);
    return reply;
  }
  const Vec2& p = waypoints_[m.seq];
  mav::MissionItemInt item;
  item.target_system = gcs_system;
  item.target_component = gcs_component;
  item.seq = m.seq;
  item.frame = static_cast<std::uint8_t>(mav::MavFrame::kLocalNed);
  item.command = static_cast<std::uint16_t>(mav::MavCmd::kNavWaypoint);
  item.autocontinue = 1;
  item.x = toLocalInt(p.x());
  item.y = toLocalInt(-p.y());
  item.param4 = std::numeric_limits<float>::quiet_NaN();  // yaw: unchanged
  reply.item = item;
  return reply;
}

MissionReply MissionStore::onClearAll(const mav::MissionClearAll& m, std::uint8_t gcs_system,
                                      std::uint8_t gcs_component) {
  MissionReply reply;
  if (m.mission_type == static_cast<std::uint8_t>(mav::MavMissionType::kMission) ||
      m.mission_type == static_cast<std::uint8_t>(mav::MavMissionType::kAll)) {
    upload_.reset();
    waypoints_.clear();
    ++mission_id_;
  }
  reply.ack = ack(gcs_system, gcs_component, mav::MavMissionResult::kAccepted, m.mission_type);
  return reply;
}

std::vector<MissionLeg> missionLegs(const Pose2& start, const std::vector<Vec2>& waypoints,
                                    double quantum_rad) {
  std::vector<Vec2> points;
  points.reserve(waypoints.size() + 1);
  points.emplace_back(start.x, start.y);
  points.insert(points.end(), waypoints.begin(), waypoints.end());
  const TravelPlan plan = makeTravelPlan(points, start.theta, quantum_rad);
  std::vector<MissionLeg> legs;
  legs.reserve(plan.segments.size());
  std::size_t item = 0;  // next waypoint not yet assigned to a leg
  for (const TravelSegment& s : plan.segments) {
    // The segment ends at a waypoint (compression keeps input points); find it in order.
    std::size_t j = item;
    while (j < waypoints.size() && (waypoints[j] - s.to).norm() > 1e-9)
      ++j;
    if (j == waypoints.size())
      j = waypoints.empty() ? 0 : waypoints.size() - 1;  // cannot happen; be safe
    legs.push_back({s, static_cast<std::uint16_t>(j)});
    item = j + 1;
  }
  if (!legs.empty() && !waypoints.empty())
    legs.back().last_item = static_cast<std::uint16_t>(waypoints.size() - 1);
  return legs;
}

}  // namespace irgs::app
