#pragma once
// Turns the sonar readings of telemetry samples into occupancy grid updates: each reading is a
// cone placed at its sonar's mount on the pose the robot believes it has (odometry), since
// that is all a real ground station knows.

#include <optional>
#include <vector>

#include "core/mapping/occupancy_grid.hpp"
#include "core/robot/robot_profile.hpp"
#include "core/robot/telemetry.hpp"

namespace irgs {

// What integrate() did with the readings of one sample.
struct SonarMapStats {
  int integrated = 0;  // readings turned into a cone update
  int skipped = 0;     // unusable: unknown sensor index, NaN/negative range, pose not finite or
                       // beyond the grid's addressable cells
};

class SonarMapper {
 public:
  // valid_distance_m is paper 003's user-specified "valid distance" (position revision case 4):
  // an echo farther than it is treated as no echo up to it, because beyond it interference and
  // specular reflection spoil the data. nullopt means each sensor's max range; a larger value
  // is capped at each sensor's max range. Throws std::invalid_argument for a sonar whose beam is
  // not in (0, pi), whose max range is not finite and > 0 or whose mount is not finite, for an
  // invalid model (sonarInverseModelError) or a valid distance that is not > 0.
  explicit SonarMapper(const RobotProfile& profile, SonarInverseModel model = {},
                       std::optional<double> valid_distance_m = std::nullopt);

  // Integrates every sonar reading of the sample into the grid. Never throws for bad readings:
  // they are counted in the result and left out.
  SonarMapStats integrate(const TelemetrySample& sample, OccupancyGrid& grid) const;

  const SonarInverseModel& model() const { return model_; }
  std::size_t sensorCount() const { return sensors_.size(); }
  // Effective valid distance of sensor i (metres). Precondition: i < sensorCount().
  double validDistance_m(std::size_t sensor) const { return sensors_.at(sensor).valid_distance_m; }

 private:
  struct Sensor {
    Pose2 mount;  // body frame
    double beam_width_rad = 0.0;
    double valid_distance_m = 0.0;
  };
  std::vector<Sensor> sensors_;
  SonarInverseModel model_;
};

}  // namespace irgs
