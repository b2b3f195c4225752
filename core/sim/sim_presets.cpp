#include "core/sim/sim_presets.hpp"

namespace irgs {

SimConfig typicalSimConfig(SimConfig base) {
  base.odometry.left_scale = 1.0005;
  base.odometry.right_scale = 0.9995;
  base.odometry.wheelbase_scale = 1.005;
  base.odometry.slip_stddev = 0.001;
  // Floor sensors (mouse profiles only): [A] 0.5 % common surface scale error, 1 % random per
  // axis and interval, as in docs/localization.md's drift table (004 gives no figures).
  base.mouse_noise.scale_error = 0.005;
  base.mouse_noise.relative_stddev = 0.01;
  return base;
}

SimConfig idealSimConfig(SimConfig base) {
  base.odometry = OdometryErrorModel{};
  base.caster_errors = CasterErrorModel{};  // the three-caster robot's wheels too
  base.sonar.range_stddev_m = 0.0;
  base.sonar.range_stddev_per_m = 0.0;
  base.sonar.dropout_probability = 0.0;
  base.proximity_stddev_m = 0.0;
  return base;
}

}  // namespace irgs
