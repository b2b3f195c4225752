#include "core/motion/sonar_memory.hpp"

#include <cmath>

namespace irgs::motion {

SonarMemory::SonarMemory(const MotionGeometry& geometry, double valid_distance_m, double max_age_s)
    : geometry_(&geometry),
      roles_(findSonarRoles(geometry)),
      valid_distance_m_(valid_distance_m),
      max_age_s_(max_age_s) {}

void SonarMemory::update(const MotionInput& input) {
  now_s_ = input.time_s;
  for (std::size_t k = 0; k < input.sonar_count; ++k) {
    const SonarReading& r = input.sonar[k];
    if (r.sensor < 0 || static_cast<std::size_t>(r.sensor) >= geometry_->sonar_count)
      continue;
    Last& l = last_[static_cast<std::size_t>(r.sensor)];
    l.time_s = input.time_s;
    l.echo = r.echo && std::isfinite(r.range_m) && r.range_m >= 0.0;
    l.range_m = r.range_m;
  }
}

std::optional<double> SonarMemory::range(int sensor) const {
  if (sensor < 0 || static_cast<std::size_t>(sensor) >= geometry_->sonar_count)
    return std::nullopt;
  const Last& l = last_[static_cast<std::size_t>(sensor)];
  if (!l.echo || l.time_s < min_time_s_ || now_s_ - l.time_s > max_age_s_ ||
      l.range_m > valid_distance_m_)
    return std::nullopt;
  return l.range_m;
}

bool SonarMemory::updatedNow(int sensor) const {
  if (sensor < 0 || static_cast<std::size_t>(sensor) >= geometry_->sonar_count)
    return false;
  return last_[static_cast<std::size_t>(sensor)].time_s == now_s_;
}

std::optional<double> SonarMemory::sideDistance(int sensor) const {
  const auto r = range(sensor);
  if (!r)
    return std::nullopt;
  const Pose2& m = geometry_->sonars[static_cast<std::size_t>(sensor)].mount;
  const double along = std::abs(std::cos(m.theta)) > 0.7 ? m.x : std::abs(m.y);
  return *r + along;
}

std::optional<double> SonarMemory::frontDistance() const {
  std::optional<double> best;
  for (std::size_t k = 0; k < roles_.forward_count; ++k) {
    const auto d = sideDistance(roles_.forward[k]);
    if (d && (!best || *d < *best))
      best = d;
  }
  return best;
}

}  // namespace irgs::motion
