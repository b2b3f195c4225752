#pragma once
// Robot-side motion primitives: what the ground station asks a robot to do on its own, and what
// the robot reports back (thesis 003_…, section 4.1; digest 7.2). The control loops of these
// primitives run where the wheels are — in the firmware, in `irgs-robot`, in the in-process
// simulator — on the robot's own odometry and sonar at its own control rate; the host only
// sends a primitive and reacts to reports, so a slow, late link costs waiting time, never
// stability.
//
// Firmware-grade vocabulary: plain values of fixed size (no heap, no strings), usable on a
// microcontroller. Frames: the robot's odometry frame (x forward at start, y left, theta CCW),
// SI units.

#include <array>
#include <cstdint>
#include <variant>

#include "core/geometry/types.hpp"

namespace irgs::motion {

// Waypoints of one segment list (turning points of the traveling algorithm, 003 section 4.3).
inline constexpr std::size_t kMaxWaypoints = 32;

// Turn on the spot, by an angle or to a heading. quantum_rad > 0 rounds the turn to multiples
// of it (the thesis's 15-degree turns); rate 0 is the robot's default.
struct TurnSpec {
  double angle_rad = 0.0;  // relative (CCW positive) unless absolute
  bool absolute = false;   // angle_rad is a heading in the odometry frame
  double quantum_rad = 0.0;
  double rate_radps = 0.0;
  friend bool operator==(const TurnSpec&, const TurnSpec&) = default;
};

// Drive straight (heading held) a signed distance. stop_at_wall ends it early (kFrontWall)
// when the forward sonars see something closer than clearance_m ahead of the body origin.
struct DriveSpec {
  double distance_m = 0.0;
  double speed_mps = 0.0;  // 0: the robot's default
  bool stop_at_wall = true;
  double clearance_m = 0.0;  // 0: the robot's default (its wall-follow distance + margin)
  friend bool operator==(const DriveSpec&, const DriveSpec&) = default;
};

// Follow a wall on one side at a set distance with the four position revisions. Starts by
// seeking (straight ahead until a wall, then revision (a)) unless one is beside the robot.
// Ends on travel_limit_m (0: none), and, when asked, on the wall ending (kWallLost, not at a
// convex corner the follower turns round) or a wall ahead (kFrontWall, before turning).
// report_every_m > 0: a kDistanceMark report each time that much more path is driven (the
// host's position-index spacing, thesis Fig. 3.7).
struct FollowWallSpec {
  bool wall_on_left = true;
  double distance_m = 0.3;
  double speed_mps = 0.0;  // 0: the robot's default
  double travel_limit_m = 0.0;
  bool stop_when_lost = false;
  bool stop_at_front_wall = false;
  double report_every_m = 0.0;
  friend bool operator==(const FollowWallSpec&, const FollowWallSpec&) = default;
};

// The traveling algorithm (003 section 4.3): from where the robot stands, turn on the spot
// toward each waypoint in turn and drive straight to it; a kTurningPoint report at each.
struct SegmentsSpec {
  std::array<Vec2, kMaxWaypoints> points{};
  std::uint8_t count = 0;
  double speed_mps = 0.0;    // 0: the robot's default
  double quantum_rad = 0.0;  // turns rounded to multiples of this (0: exact)
  // End with kFrontWall when something is ahead within the clearance: only when it lies before
  // the waypoint (travel on a known map), or anywhere ahead (exploring: any wall met counts).
  bool stop_at_wall = true;
  bool stop_beyond_waypoint = false;
  double clearance_m = 0.0;  // 0: the robot's default
  bool append(const Vec2& p) {
    if (count >= kMaxWaypoints)
      return false;
    points[count++] = p;
    return true;
  }
};

// Path following of paper 004 (digest 5.6) along a polyline of waypoints, steering with the
// Lyapunov law of core/estimation/path_following.hpp; a kTurningPoint report at each vertex.
struct FollowPathSpec {
  std::array<Vec2, kMaxWaypoints> points{};
  std::uint8_t count = 0;
  double speed_mps = 0.0;
  bool append(const Vec2& p) {
    if (count >= kMaxWaypoints)
      return false;
    points[count++] = p;
    return true;
  }
};

using PrimitiveSpec =
    std::variant<TurnSpec, DriveSpec, FollowWallSpec, SegmentsSpec, FollowPathSpec>;

enum class PrimitiveKind : std::uint8_t { kTurn, kDrive, kFollowWall, kSegments, kFollowPath };
inline PrimitiveKind kindOf(const PrimitiveSpec& spec) {
  return static_cast<PrimitiveKind>(spec.index());
}
const char* toString(PrimitiveKind kind);

// A primitive with the id its reports carry (chosen by the host; 0 is never used).
struct Primitive {
  std::uint16_t id = 0;
  PrimitiveSpec spec;
};

enum class ReportKind : std::uint8_t {
  kStarted,       // accepted and running
  kRefused,       // not started (reason says why)
  kTurningPoint,  // segments/path: waypoint `index` reached
  kDistanceMark,  // follow wall: report_every_m more driven (distance_m = total)
  kMode,          // follow wall: the follower changed mode (index = motion::WallFollowMode)
  kContact,       // follow wall: a bumper or a stall; the follower backs off and goes on
  kWallLost,      // follow wall: the side wall ended (stop_when_lost), or never found
  kFrontWall,     // a wall ahead ended it (drive/segments stop_at_wall, follow stop_at_front_wall)
  kDone,          // finished as asked
  kFailed,        // could not finish (reason says why)
  kCancelled,     // the host cancelled it, or a newer primitive replaced it
};
const char* toString(ReportKind kind);

enum class Reason : std::uint8_t {
  kNone,
  kInvalid,      // a non-finite, out-of-range or empty specification
  kUnsupported,  // this robot cannot run this kind
  kBumped,       // a bumper or a stall stopped a forward move
  kBlocked,      // in contact for the blocked time while turning or backing up
  kNoProgress,   // the watchdog saw no progress (stuck against something the bumpers miss)
  kSafety,       // a safety stop (e-stop, ground station silent, bumper brake)
  kNoSensors,    // the sonars the primitive needs are missing
  kNoAnswer,     // the robot never answered the start (a link that stayed silent)
};
const char* toString(Reason reason);

// One report, stamped with the robot's time and its odometry pose at that moment.
struct MotionReport {
  std::uint16_t id = 0;  // the primitive's
  ReportKind kind = ReportKind::kStarted;
  Reason reason = Reason::kNone;
  double time_s = 0.0;
  Pose2 pose;               // odometry
  double distance_m = 0.0;  // path length driven by this primitive so far
  std::int16_t index = -1;  // waypoint, corner-turn revision (0 = a, 1 = b, 2 = c)
  friend bool operator==(const MotionReport&, const MotionReport&) = default;
};

// True for the reports after which the primitive no longer runs.
inline bool isFinal(ReportKind kind) {
  return kind == ReportKind::kRefused || kind == ReportKind::kDone || kind == ReportKind::kFailed ||
         kind == ReportKind::kCancelled || kind == ReportKind::kWallLost ||
         kind == ReportKind::kFrontWall;
}

}  // namespace irgs::motion
