#pragma once
// The wall model of paper 000 (digest 1.3, ambiguities A000-8/A000-9): a wall face as a line in
// polar normal form plus a visibility sign, and the distance/bearing a sensor predicts for it.
//
//   line:  x cos(phi) + y sin(phi) = P_R,   P_R >= 0 the distance from the world origin to the
//          line, phi the direction of that perpendicular (origin -> line) from world +x.
//   P_V:   +1 when the face is visible from the world origin, -1 otherwise.
// A thin wall has two faces; each face is its own WallLine (same P_R and phi, opposite P_V).
// Angles are returned wrapped to (-pi, pi] (paper 000's Table 1 prints 0..360 deg).

#include <array>

#include "core/geometry/types.hpp"

namespace irgs {

struct WallLine {
  double p_r_m = 0.0;
  double phi_rad = 0.0;
  int p_v = 1;
};

// Robot-facing normal form (A000-9): phi_eff is the direction from a sensor in front of the face
// towards the wall, and x cos(phi_eff) + y sin(phi_eff) = p_eff_m (p_eff may be negative).
// phi_eff = phi, P_eff = P_R when P_V = +1; phi_eff = phi + pi, P_eff = -P_R when P_V = -1.
struct FacingLine {
  double phi_eff_rad = 0.0;
  double p_eff_m = 0.0;
};

// Lines through the origin closer than this (m) get P_R = 0 and P_V = +1 (the origin lies on the
// line, so "visible from the origin" is decided in favour of the face): phi is then the direction
// opposite the face normal.
inline constexpr double kWallOnOriginTolerance_m = 1e-9;

// The face of `wall` whose outward normal points to the side of `face_normal` (only its component
// perpendicular to the wall matters). Throws std::invalid_argument for a zero-length wall or a
// face_normal without a perpendicular component.
WallLine wallLineFromFace(const Segment& wall, const Vec2& face_normal);
// The face of `wall` seen from `viewpoint` (a point beside the wall, e.g. the robot or a room's
// inside). Throws std::invalid_argument when the wall has zero length or viewpoint is on its line.
WallLine wallLineFacing(const Segment& wall, const Vec2& viewpoint);
// Both faces of a thin wall: [0] the face on the left of a -> b, [1] the face on the right.
std::array<WallLine, 2> wallLineFaces(const Segment& wall);

FacingLine robotFacing(const WallLine& wall);

// (17) d^ = P_V (P_R - x_T cos(phi) - y_T sin(phi)): perpendicular distance from the sensor
// (transmitter) position to the wall line, positive when the sensor is in front of the face.
double predictedWallDistance(const WallLine& wall, const Pose2& sensor);
// (16) theta^ = phi_eff - phi_T with phi_T the sensor's world heading (A000-9: phi_eff instead of
// phi, so P_V = -1 faces are not off by pi): bearing of the wall normal relative to the sensor
// boresight, wrapped to (-pi, pi].
double predictedWallBearing(const WallLine& wall, const Pose2& sensor);

// (18)/(19) distance from the sensor to a corner or edge point, and its bearing relative to the
// boresight (for points the paper uses the distance only; the bearing serves matching).
double predictedPointDistance(const Vec2& point, const Pose2& sensor);
double predictedPointBearing(const Vec2& point, const Pose2& sensor);

}  // namespace irgs
