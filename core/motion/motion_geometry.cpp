#include "core/motion/motion_geometry.hpp"

#include <cmath>

namespace irgs::motion {
namespace {

constexpr double kRoleTolerance = degToRad(20.0);

bool facing(const Pose2& mount, double heading_rad) {
  return std::abs(wrapAngle(mount.theta - heading_rad)) <= kRoleTolerance;
}

SonarRoles::SidePair findSidePair(const MotionGeometry& g, double side_heading) {
  SonarRoles::SidePair pair;
  for (std::size_t i = 0; i < g.sonar_count; ++i) {
    const Pose2& a = g.sonars[i].mount;
    if (!facing(a, side_heading))
      continue;
    if (pair.front < 0)
      pair.front = static_cast<int>(i);  // a single side sonar still allows following
    for (std::size_t j = 0; j < g.sonar_count; ++j) {
      const Pose2& b = g.sonars[j].mount;
      if (j == i || !facing(b, side_heading))
        continue;
      const double baseline = a.x - b.x;  // a ahead of b
      if (baseline > pair.baseline_m) {
        pair.front = static_cast<int>(i);
        pair.rear = static_cast<int>(j);
        pair.baseline_m = baseline;
      }
    }
  }
  return pair;
}

}  // namespace

SonarRoles findSonarRoles(const MotionGeometry& g) {
  SonarRoles roles;
  for (std::size_t i = 0; i < g.sonar_count; ++i) {
    if (facing(g.sonars[i].mount, 0.0))
      roles.forward[roles.forward_count++] = static_cast<std::int8_t>(i);
  }
  for (std::size_t a = 0; a < roles.forward_count; ++a) {
    for (std::size_t b = 0; b < roles.forward_count; ++b) {
      const int i = roles.forward[a], j = roles.forward[b];
      const Pose2& mi = g.sonars[static_cast<std::size_t>(i)].mount;
      const Pose2& mj = g.sonars[static_cast<std::size_t>(j)].mount;
      const double baseline = mi.y - mj.y;
      if (std::abs(mi.x - mj.x) <= 0.02 && baseline > roles.front_baseline_m) {
        roles.front_left = i;
        roles.front_right = j;
        roles.front_baseline_m = baseline;
      }
    }
  }
  roles.left = findSidePair(g, 0.5 * kPi);
  roles.right = findSidePair(g, -0.5 * kPi);
  return roles;
}

}  // namespace irgs::motion
