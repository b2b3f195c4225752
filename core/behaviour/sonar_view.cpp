#include "core/behaviour/sonar_view.hpp"

#include <cmath>

namespace irgs {
namespace {

constexpr double kRoleTolerance = degToRad(20.0);

SonarRoles::SidePair findSidePair(const RobotProfile& profile, double side_heading) {
  SonarRoles::SidePair pair;
  for (std::size_t i = 0; i < profile.sonars.size(); ++i) {
    const Pose2& a = profile.sonars[i].mount;
    if (std::abs(wrapAngle(a.theta - side_heading)) > kRoleTolerance)
      continue;
    if (pair.front < 0) {
      pair.front = static_cast<int>(i);  // a single side sonar still allows following
    }
    for (std::size_t j = 0; j < profile.sonars.size(); ++j) {
      const Pose2& b = profile.sonars[j].mount;
      if (j == i || std::abs(wrapAngle(b.theta - side_heading)) > kRoleTolerance)
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

SonarRoles findSonarRoles(const RobotProfile& profile) {
  SonarRoles roles;
  const auto& s = profile.sonars;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (std::abs(wrapAngle(s[i].mount.theta)) <= kRoleTolerance)
      roles.forward.push_back(static_cast<int>(i));
  }
  for (int i : roles.forward) {
    for (int j : roles.forward) {
      const Pose2& a = s[static_cast<std::size_t>(i)].mount;
      const Pose2& b = s[static_cast<std::size_t>(j)].mount;
      const double baseline = a.y - b.y;
      if (std::abs(a.x - b.x) <= 0.02 && baseline > roles.front_baseline_m) {
        roles.front_left = i;
        roles.front_right = j;
        roles.front_baseline_m = baseline;
      }
    }
  }
  roles.left = findSidePair(profile, 0.5 * kPi);
  roles.right = findSidePair(profile, -0.5 * kPi);
  return roles;
}

SonarView::SonarView(const RobotProfile& profile, double valid_distance_m, double max_age_s)
    : profile_(profile),
      roles_(findSonarRoles(profile)),
      last_(profile.sonars.size()),
      valid_distance_m_(valid_distance_m),
      max_age_s_(max_age_s) {}

void SonarView::update(const TelemetrySample& sample) {
  now_s_ = sample.time_s;
  for (const SonarReading& r : sample.sonar) {
    if (r.sensor < 0 || static_cast<std::size_t>(r.sensor) >= last_.size())
      continue;
    Last& l = last_[static_cast<std::size_t>(r.sensor)];
    l.time_s = sample.time_s;
    l.echo = r.echo && std::isfinite(r.range_m) && r.range_m >= 0.0;
    l.range_m = r.range_m;
  }
}

std::optional<double> SonarView::range(int sensor) const {
  if (sensor < 0 || static_cast<std::size_t>(sensor) >= last_.size())
    return std::nullopt;
  const Last& l = last_[static_cast<std::size_t>(sensor)];
  if (!l.echo || l.time_s < min_time_s_ || now_s_ - l.time_s > max_age_s_ ||
      l.range_m > valid_distance_m_)
    return std::nullopt;
  return l.range_m;
}

bool SonarView::updatedNow(int sensor) const {
  if (sensor < 0 || static_cast<std::size_t>(sensor) >= last_.size())
    return false;
  return last_[static_cast<std::size_t>(sensor)].time_s == now_s_;
}

std::optional<double> SonarView::sideDistance(int sensor) const {
  const auto r = range(sensor);
  if (!r)
    return std::nullopt;
  const Pose2& m = profile_.sonars[static_cast<std::size_t>(sensor)].mount;
  const double along = std::abs(std::cos(m.theta)) > 0.7 ? m.x : std::abs(m.y);
  return *r + along;
}

std::optional<double> SonarView::frontDistance() const {
  std::optional<double> best;
  for (int i : roles_.forward) {
    const auto d = sideDistance(i);
    if (d && (!best || *d < *best))
      best = d;
  }
  return best;
}

}  // namespace irgs
