#include "core/mapping/sonar_mapper.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace irgs {

SonarMapper::SonarMapper(const RobotProfile& profile, SonarInverseModel model,
                         std::optional<double> valid_distance_m)
    : model_(model) {
  if (const auto error = sonarInverseModelError(model_))
    throw std::invalid_argument("SonarMapper: invalid model: " + *error);
  if (valid_distance_m && !(*valid_distance_m > 0.0))
    throw std::invalid_argument("SonarMapper: valid distance must be > 0, got " +
                                std::to_string(*valid_distance_m));
  sensors_.reserve(profile.sonars.size());
  for (std::size_t i = 0; i < profile.sonars.size(); ++i) {
    const SonarSpec& spec = profile.sonars[i];
    const std::string who = "SonarMapper: sonar " + std::to_string(i) + " '" + spec.name + "': ";
    if (!(spec.beam_width_rad > 0.0 && spec.beam_width_rad < kPi))
      throw std::invalid_argument(who + "beam width must be in (0, 180) degrees");
    if (!std::isfinite(spec.max_range_m) || !(spec.max_range_m > 0.0))
      throw std::invalid_argument(who + "max range must be finite and > 0");
    if (!std::isfinite(spec.mount.x) || !std::isfinite(spec.mount.y) ||
        !std::isfinite(spec.mount.theta))
      throw std::invalid_argument(who + "mount pose must be finite");
    const double valid = std::min(valid_distance_m.value_or(spec.max_range_m), spec.max_range_m);
    sensors_.push_back({spec.mount, spec.beam_width_rad, valid});
  }
}

SonarMapStats SonarMapper::integrate(const TelemetrySample& sample, OccupancyGrid& grid) const {
  SonarMapStats stats;
  const Pose2& pose = sample.odometry_pose;
  const bool pose_ok = std::isfinite(pose.x) && std::isfinite(pose.y) && std::isfinite(pose.theta);
  for (const SonarReading& reading : sample.sonar) {
    if (!pose_ok || reading.sensor < 0 ||
        static_cast<std::size_t>(reading.sensor) >= sensors_.size()) {
      ++stats.skipped;
      continue;
    }
    const Sensor& sensor = sensors_[static_cast<std::size_t>(reading.sensor)];
    bool echo = reading.echo;
    double range_m = sensor.valid_distance_m;  // no echo: nothing up to the valid distance
    if (echo) {
      if (!std::isfinite(reading.range_m) || reading.range_m < 0.0) {
        ++stats.skipped;
        continue;
      }
      if (reading.range_m > sensor.valid_distance_m)
        echo = false;  // beyond the valid distance: no echo up to it (paper 003, case 4)
      else
        range_m = reading.range_m;
    }
    const Pose2 sonar_pose = pose.compose(sensor.mount);
    const Vec2 apex = sonar_pose.position();
    const double reach = range_m + model_.arc_thickness_m;
    if (!grid.isAddressable(apex, reach + 4.0 * grid.resolution_m()) ||
        reach / grid.resolution_m() > OccupancyGrid::kMaxConeRadiusCells) {
      ++stats.skipped;
      continue;
    }
    grid.integrateSonar(apex, sonar_pose.theta, sensor.beam_width_rad, range_m, echo, model_);
    ++stats.integrated;
  }
  return stats;
}

}  // namespace irgs
