#pragma once
// Vocabulary of plane geometry shared by every part of IRGS.
//
// Frames (one statement for the whole project, see docs/decisions.md):
//   world: x, y on the floor, z up, metres.
//   body:  x forward, y left, origin midway between the drive wheels.
//   heading theta: counter-clockwise from world +x, radians, wrapped to (-pi, pi].
// Degrees appear only at the user's edge (files written by people, the GUI).

#include <Eigen/Core>
#include <cmath>
#include <limits>
#include <numbers>

namespace irgs {

using Vec2 = Eigen::Vector2d;

inline constexpr double kPi = std::numbers::pi;

// Wraps an angle to (-pi, pi].
inline double wrapAngle(double angle_rad) {
  double a = std::remainder(angle_rad, 2.0 * kPi);  // [-pi, pi]
  if (a <= -kPi)
    a += 2.0 * kPi;
  return a;
}

inline constexpr double degToRad(double deg) {
  return deg * kPi / 180.0;
}
inline constexpr double radToDeg(double rad) {
  return rad * 180.0 / kPi;
}

// z component of the 2-D cross product: > 0 when b is counter-clockwise from a.
inline double cross(const Vec2& a, const Vec2& b) {
  return a.x() * b.y() - a.y() * b.x();
}

// A planar rigid pose: position of the body origin in the world and its heading.
struct Pose2 {
  double x = 0.0;
  double y = 0.0;
  double theta = 0.0;

  Vec2 position() const { return {x, y}; }
  Vec2 heading() const { return {std::cos(theta), std::sin(theta)}; }

  // Maps a point given in this pose's body frame to the world frame.
  Vec2 toWorld(const Vec2& body_point) const {
    const double c = std::cos(theta), s = std::sin(theta);
    return {x + c * body_point.x() - s * body_point.y(),
            y + s * body_point.x() + c * body_point.y()};
  }
  // Maps a world point into this pose's body frame.
  Vec2 toBody(const Vec2& world_point) const {
    const double c = std::cos(theta), s = std::sin(theta);
    const double dx = world_point.x() - x, dy = world_point.y() - y;
    return {c * dx + s * dy, -s * dx + c * dy};
  }
  // this ⊕ other: other is expressed in this pose's body frame.
  Pose2 compose(const Pose2& other) const {
    const Vec2 p = toWorld({other.x, other.y});
    return {p.x(), p.y(), wrapAngle(theta + other.theta)};
  }
  // ⊖this: the world origin seen from this pose, so that compose(inverse()) is the identity.
  Pose2 inverse() const {
    const Vec2 p = toBody(Vec2::Zero());
    return {p.x(), p.y(), wrapAngle(-theta)};
  }

  friend bool operator==(const Pose2&, const Pose2&) = default;
};

// A straight segment from a to b.
struct Segment {
  Vec2 a = Vec2::Zero();
  Vec2 b = Vec2::Zero();

  double length() const { return (b - a).norm(); }
  Vec2 direction() const { return (b - a).normalized(); }
  // Unit normal on the left of a -> b.
  Vec2 leftNormal() const {
    const Vec2 d = direction();
    return {-d.y(), d.x()};
  }
};

// Axis-aligned bounding box; empty when min > max.
struct Box2 {
  Vec2 min{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  Vec2 max{-std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};

  bool empty() const { return min.x() > max.x() || min.y() > max.y(); }
  void extend(const Vec2& p) {
    min = min.cwiseMin(p);
    max = max.cwiseMax(p);
  }
  void extend(const Box2& other) {
    if (other.empty())
      return;
    extend(other.min);
    extend(other.max);
  }
  bool contains(const Vec2& p) const {
    return p.x() >= min.x() && p.x() <= max.x() && p.y() >= min.y() && p.y() <= max.y();
  }
  Vec2 size() const { return empty() ? Vec2::Zero() : Vec2(max - min); }
};

}  // namespace irgs
