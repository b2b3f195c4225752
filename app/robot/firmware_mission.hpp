#pragma once
// Mission (path) handling of the firmware (MAVLink mission protocol, docs/protocol.md section
// 13). Pure: no clock, the caller passes the firmware time.
//
// * MissionStore: upload (MISSION_COUNT -> MISSION_REQUEST_INT n -> MISSION_ITEM_INT n ... ->
//   MISSION_ACK), with a re-request every kItemTimeout_s and a give-up after kMaxRetries;
//   download (MISSION_REQUEST_LIST -> MISSION_COUNT, MISSION_REQUEST_INT -> MISSION_ITEM_INT);
//   MISSION_CLEAR_ALL. Items are MAV_CMD_NAV_WAYPOINT in MAV_FRAME_LOCAL_NED (x north = our
//   world x, y east = minus our world y, metres * 1e4) or MAV_FRAME_LOCAL_FLU (our world frame).
// * missionLegs(): the path from the robot's position through the waypoints as the thesis
//   traveling algorithm's segments (core/planning/traveling.hpp: turn on the spot, then
//   straight), each tagged with the last mission item it reaches (collinear items are merged
//   into a segment and reported reached when the robot passes its end).

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "comms/mavlink/messages.hpp"
#include "core/geometry/types.hpp"
#include "core/planning/traveling.hpp"

namespace irgs::app {

inline constexpr std::size_t kMaxMissionItems = 512;

// What the store wants sent back; at most one of each per call.
struct MissionReply {
  std::optional<comms::mavlink::MissionRequestInt> request;
  std::optional<comms::mavlink::MissionItemInt> item;
  std::optional<comms::mavlink::MissionCount> count;
  std::optional<comms::mavlink::MissionAck> ack;
  std::string status;  // a STATUSTEXT line for the operator, empty for none
  bool warning = false;
};

class MissionStore {
 public:
  static constexpr double kItemTimeout_s = 0.5;
  static constexpr int kMaxRetries = 5;

  explicit MissionStore(std::uint8_t system_id, std::uint8_t component_id);

  // `gcs_system`/`gcs_component`: the sender, the target of our replies.
  MissionReply onCount(const comms::mavlink::MissionCount& m, std::uint8_t gcs_system,
                       std::uint8_t gcs_component, double now_s);
  MissionReply onItem(const comms::mavlink::MissionItemInt& m, std::uint8_t gcs_system,
                      std::uint8_t gcs_component, double now_s);
  MissionReply onRequestList(const comms::mavlink::MissionRequestList& m, std::uint8_t gcs_system,
                             std::uint8_t gcs_component);
  MissionReply onRequest(const comms::mavlink::MissionRequestInt& m, std::uint8_t gcs_system,
                         std::uint8_t gcs_component);
  MissionReply onClearAll(const comms::mavlink::MissionClearAll& m, std::uint8_t gcs_system,
                          std::uint8_t gcs_component);
  // Re-requests the awaited item after kItemTimeout_s, gives up after kMaxRetries.
  MissionReply poll(double now_s);

  bool uploading() const { return upload_.has_value(); }
  // The stored waypoints (our world frame, metres), in mission order.
  const std::vector<Vec2>& waypoints() const { return waypoints_; }
  // Changes with every accepted upload or clear (MISSION_ACK / MISSION_CURRENT opaque id).
  std::uint32_t missionId() const { return mission_id_; }

 private:
  struct Upload {
    std::uint16_t count = 0;
    std::uint16_t next = 0;
    std::vector<Vec2> points;
    std::uint8_t gcs_system = 0;
    std::uint8_t gcs_component = 0;
    double requested_at_s = 0.0;
    int retries = 0;
  };
  comms::mavlink::MissionRequestInt requestFor(const Upload& u) const;
  comms::mavlink::MissionAck ack(std::uint8_t gcs_system, std::uint8_t gcs_component,
                                 comms::mavlink::MavMissionResult result,
                                 std::uint8_t mission_type = 0) const;

  std::uint8_t system_id_;
  std::uint8_t component_id_;
  std::optional<Upload> upload_;
  std::vector<Vec2> waypoints_;
  std::uint32_t mission_id_ = 0;
};

// One leg of a mission: turn to `segment.heading_rad`, drive to `segment.to`; on arrival the
// items up to and including `last_item` are reached.
struct MissionLeg {
  TravelSegment segment;
  std::uint16_t last_item = 0;
};

// The legs from `start` (odometry pose) through `waypoints`; quantum as makeTravelPlan (0 =
// exact turns, the firmware's default since it steers by odometry). Waypoints the robot is
// already at, and collinear ones, are folded into the neighbouring legs.
std::vector<MissionLeg> missionLegs(const Pose2& start, const std::vector<Vec2>& waypoints,
                                    double quantum_rad = 0.0);

}  // namespace irgs::app
