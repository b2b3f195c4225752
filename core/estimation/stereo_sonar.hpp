#pragma once
// The stereo ultrasonic sensor of paper 000 (digest 1.2): one transmitter T midway between two
// receivers R1 and R2. From the two echo path lengths r1 (T -> reflector -> R1) and r2 it gives
// the distance d from T to a reflector and the reflector's bearing theta.
//
// Sensor frame (digest 1.2 [D]): origin at T, boresight +x_s, baseline along y_s (left).
//   R1 = (0, -s) (right of the boresight), R2 = (0, +s) (left), s = half the baseline.
//   theta = direction of the wall normal (from T towards the wall) or of a corner/edge point,
//   counter-clockwise from the boresight; theta > 0 puts R1 farther away, so r1 > r2 (7)/(8).
// A sensor's world pose (Pose2) is the pose of T with theta = boresight direction.
// Lengths in metres, angles in radians, times in seconds.

#include <cstdint>

#include "core/geometry/types.hpp"
#include "core/world/wall_model.hpp"

namespace irgs {

struct StereoSonarParams {
  double half_baseline_m = 0.2;       // s: T to each receiver [000: 0.2 m]
  double speed_of_sound_mps = 343.0;  // [A] 20 degC; paper 000 does not state it
  double max_tof_s = 0.012;           // longer echoes are discarded [000: 12 ms]
};

// Throws std::invalid_argument unless s > 0, c > 0 and max_tof > 0 (all finite).
void validate(const StereoSonarParams& params);

// Acoustic path lengths of one echo: r1 to R1 (right receiver), r2 to R2 (left receiver).
struct EchoPaths {
  double r1_m = 0.0;
  double r2_m = 0.0;
};

// Receiver positions of a sensor whose transmitter has the world pose `sensor`.
Vec2 receiver1Position(const Pose2& sensor, double half_baseline_m);  // R1, right
Vec2 receiver2Position(const Pose2& sensor, double half_baseline_m);  // R2, left

// Forward models (noise free). Wall: specular reflection by the mirror image T' of T in the
// wall's line, r_i = |T' - R_i|; this equals (3)/(4). Only meaningful when the sensor is in
// front of the face (predictedWallDistance > 0).
EchoPaths wallEchoPaths(const WallLine& wall, const Pose2& sensor, double half_baseline_m);
// (3)/(4) in closed form for a wall at distance d and bearing theta in the sensor frame.
EchoPaths wallEchoPathsLocal(double d_m, double theta_rad, double half_baseline_m);
// Concave corner C (two perpendicular walls, a retro-reflector): image of T is 2C - T, so
// r_i = |2C - T - R_i| [D].
EchoPaths cornerEchoPaths(const Vec2& corner, const Pose2& sensor, double half_baseline_m);
// Convex edge E (point diffractor): r_i = |E - T| + |E - R_i| [D].
EchoPaths edgeEchoPaths(const Vec2& edge, const Pose2& sensor, double half_baseline_m);

enum class InversionStatus {
  kOk,
  kNonFinite,          // r1, r2 or s not finite, or not positive
  kNegativeRadicand,   // (5): (r1^2 + r2^2)/2 - s^2 <= 0
  kBearingOutOfRange,  // (6): |(r1^2 - r2^2) / (8 s d)| >= 1
};

struct StereoInversion {
  InversionStatus status = InversionStatus::kNonFinite;
  double d_m = 0.0;        // valid only when ok()
  double theta_rad = 0.0;  // valid only when ok()
  bool ok() const { return status == InversionStatus::kOk; }
};

// (5)-(8): distance and bearing of a wall (exact also for a concave corner). The validity checks
// are the paper's "first-stage error handling".
StereoInversion invertSpecular(double r1_m, double r2_m, double half_baseline_m);
// Edge-specific inverse (digest 1.2 [D]) for a point diffractor:
//   d = (r1^2 + r2^2 - 2 s^2) / (2 (r1 + r2)),  sin(theta) = (r1 - r2)(r1 + r2 - 2 d) / (4 d s).
StereoInversion invertEdge(double r1_m, double r2_m, double half_baseline_m);

const char* toString(InversionStatus status);

// Time of flight <-> acoustic path length, path = c * tof.
double tofToPathLength(double tof_s, double speed_of_sound_mps);
double pathLengthToTof(double path_m, double speed_of_sound_mps);
// True when both echoes arrived within the max-TOF window (and are finite and positive).
bool withinMaxTof(const EchoPaths& paths, const StereoSonarParams& params);

}  // namespace irgs
