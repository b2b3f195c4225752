#include "core/world/wall_model.hpp"

#include <cmath>
#include <stdexcept>

namespace irgs {

WallLine wallLineFromFace(const Segment& wall, const Vec2& face_normal) {
  const Vec2 along = wall.b - wall.a;
  if (!(along.norm() > 0.0))
    throw std::invalid_argument("wallLineFromFace: the wall has zero length");
  const Vec2 left = Vec2(-along.y(), along.x()).normalized();
  const double side = left.dot(face_normal);
  if (!(std::abs(side) > 1e-12 * face_normal.norm()) || !std::isfinite(side))
    throw std::invalid_argument("wallLineFromFace: face_normal is parallel to the wall");
  const Vec2 n = side > 0.0 ? left : Vec2(-left);  // unit outward normal of the face

  // The line is n . p = c. The origin is in front of the face when n . 0 > c, i.e. c < 0; the
  // perpendicular from the origin to the line then runs along -n.
  const double c = n.dot(wall.a);
  WallLine line;
  Vec2 u;  // unit direction origin -> line
  if (c > kWallOnOriginTolerance_m) {
    line.p_r_m = c;
    line.p_v = -1;
    u = n;
  } else {
    line.p_r_m = std::abs(c) > kWallOnOriginTolerance_m ? -c : 0.0;
    line.p_v = 1;
    u = -n;
  }
  line.phi_rad = wrapAngle(std::atan2(u.y(), u.x()));
  return line;
}

WallLine wallLineFacing(const Segment& wall, const Vec2& viewpoint) {
  const Vec2 along = wall.b - wall.a;
  if (!(along.norm() > 0.0))
    throw std::invalid_argument("wallLineFacing: the wall has zero length");
  const double side = cross(along, viewpoint - wall.a);
  if (side == 0.0 || !std::isfinite(side))
    throw std::invalid_argument("wallLineFacing: the viewpoint lies on the wall's line");
  const Vec2 left(-along.y(), along.x());
  return wallLineFromFace(wall, side > 0.0 ? left : Vec2(-left));
}

std::array<WallLine, 2> wallLineFaces(const Segment& wall) {
  const Vec2 along = wall.b - wall.a;
  const Vec2 left(-along.y(), along.x());
  return {wallLineFromFace(wall, left), wallLineFromFace(wall, -left)};
}

FacingLine robotFacing(const WallLine& wall) {
  if (wall.p_v >= 0)
    return {wall.phi_rad, wall.p_r_m};
  return {wrapAngle(wall.phi_rad + kPi), -wall.p_r_m};
}

double predictedWallDistance(const WallLine& wall, const Pose2& sensor) {
  return wall.p_v *
         (wall.p_r_m - sensor.x * std::cos(wall.phi_rad) - sensor.y * std::sin(wall.phi_rad));
}

double predictedWallBearing(const WallLine& wall, const Pose2& sensor) {
  return wrapAngle(robotFacing(wall).phi_eff_rad - sensor.theta);
}

double predictedPointDistance(const Vec2& point, const Pose2& sensor) {
  return (point - sensor.position()).norm();
}

double predictedPointBearing(const Vec2& point, const Pose2& sensor) {
  const Vec2 d = point - sensor.position();
  return wrapAngle(std::atan2(d.y(), d.x()) - sensor.theta);
}

}  // namespace irgs
