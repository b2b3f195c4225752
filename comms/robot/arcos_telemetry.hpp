#pragma once
// Standard SIPs -> TelemetrySamples for a Pioneer-class robot (pure): robot units to SI with the
// profile's ARCOS conversion factors (arcos_params.hpp), the 15-bit position counters unwrapped,
// sonar readings by disc number, bumper bits mapped onto the profile's bumpers.
//
//   position  x, y [m] = unwrapped counter * DistConvFactor / 1000; the first SIP's value is
//             read as a signed 15-bit number (ARCOS starts at 0 after OPEN/SETO), later ones add
//             the shortest step modulo 2^15 (OdometryUnwrapper)
//   heading   theta = THPOS * AngleConvFactor, wrapped to (-pi, pi]
//   velocity  v = (L + R) / 2 * VelConvFactor / 1000; omega from ROTVEL (0.1 deg/s) when the
//             SIP carries it, else (R - L) / 2 * VelConvFactor * DiffConvFactor (ARIA's formula)
//   sonar     range = RANGE * RangeConvFactor / 1000; a range at or beyond the disc's
//             max_range_m is "no echo"; disc numbers outside the profile are skipped (counted)
//   bumpers   front bits (9-15) then rear bits (1-7), in order, onto the profile's bumpers whose
//             normal points forward (cos >= 0) and backward respectively
// Encoder ticks are not in the standard SIP; samples carry 0 ticks.
//
// Frame: with an anchor (setAnchor) the poses are re-expressed in the map frame by the rigid
// transform that puts the first SIP at the anchor, and after a reconnection (reset(): ARCOS
// counts from zero again at OPEN) by the one that puts the new first SIP where the last one
// was, so the map does not jump when a Bluetooth link drops. Without one, poses are ARCOS's.

#include <cstdint>
#include <optional>

#include "comms/arcos/arcos_sip.hpp"
#include "comms/robot/arcos_params.hpp"
#include "core/robot/robot_profile.hpp"
#include "core/robot/telemetry.hpp"

namespace irgs::comms {

// Which SIP stall/bumper bit each profile bumper reads: bit index (1-7 rear, 9-15 front) or -1.
std::vector<int> arcosBumperBits(const RobotProfile& profile);

class ArcosTelemetryConverter {
 public:
  ArcosTelemetryConverter(RobotProfile profile, ArcosParams params);

  TelemetrySample convert(const arcos::StandardSip& sip, double time_s);
  // Forget the position history (a new connection: the robot may have restarted).
  void reset();
  // Map frame: see above. Takes effect at the next first SIP.
  void setAnchor(const Pose2& start_in_map) { anchor_ = start_in_map; }

  // ARCOS odometry heading minus map heading (0 without an anchor or before the first SIP).
  double mapToOdometryHeading_rad() const { return -to_map_.theta; }

  std::uint64_t skippedSonars() const { return skipped_sonars_; }
  const ArcosParams& params() const { return params_; }

 private:
  RobotProfile profile_;
  ArcosParams params_;
  std::vector<int> bumper_bits_;
  arcos::OdometryUnwrapper x_;
  arcos::OdometryUnwrapper y_;
  std::int64_t x0_ = 0;
  std::int64_t y0_ = 0;
  bool started_ = false;
  std::optional<Pose2> anchor_;     // where the next first SIP is placed
  Pose2 to_map_;                    // map <- ARCOS odometry frame (identity without an anchor)
  std::optional<Pose2> last_pose_;  // last pose delivered (map frame)
  std::uint64_t skipped_sonars_ = 0;
};

}  // namespace irgs::comms
