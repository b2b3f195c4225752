#include "core/navigation/delivery_behaviour.hpp"

#include "core/camera/ceiling_camera_config.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace irgs {

DeliveryParams deliveryParamsFor(const RobotProfile& profile) {
  DeliveryParams p;
  const CeilingCameraConfig camera = ceilingCameraFromProfile(profile).config;
  p.navigator.tilt = camera.tilt;
  p.tilt_rate_radps = camera.tilt_rate_radps;
  p.navigator.wheel_separation_m = profile.drive.wheelbase_m;
  p.navigator.cruise_speed_mps =
      std::min(p.navigator.cruise_speed_mps, 0.9 * profile.limits.max_speed_mps);
  p.navigator.marker_min_speed_mps =
      std::min(p.navigator.marker_min_speed_mps, p.navigator.cruise_speed_mps);
  p.navigator.heading.max_turn_rate_radps =
      std::min(p.navigator.heading.max_turn_rate_radps, profile.limits.max_turn_rate_radps);
  return p;
}

DeliveryBehaviour::DeliveryBehaviour(RoutePlan route, const RobotProfile& profile,
                                     std::shared_ptr<CeilingObserver> observer,
                                     DeliveryParams params)
    : navigator_(std::move(route), params.navigator),
      observer_(std::move(observer)),
      params_(params),
      servo_(params.navigator.tilt.min_tilt_rad, params.tilt_rate_radps) {
  if (!observer_)
    throw std::invalid_argument("DeliveryBehaviour: no ceiling observer");
  for (const SonarSpec& s : profile.sonars) {
    const Vec2 dir(std::cos(s.mount.theta), std::sin(s.mount.theta));
    sonar_.push_back({dir, s.max_range_m});
    max_range_.push_back(s.max_range_m);
  }
}

VelocityCommand DeliveryBehaviour::onSample(const TelemetrySample& sample) {
  for (const SonarReading& r : sample.sonar) {
    if (r.sensor < 0 || static_cast<std::size_t>(r.sensor) >= sonar_.size())
      continue;
    const auto i = static_cast<std::size_t>(r.sensor);
    sonar_[i].range_m = r.echo ? r.range_m : max_range_[i];  // no echo: free up to max range
  }
  const double dt = std::max(0.0, sample.time_s - last_time_s_);
  last_time_s_ = sample.time_s;
  // The servo moves toward the tilt asked for last.
  const double want =
      navigator_.lastOutput().tilt_rad > 0.0 ? navigator_.lastOutput().tilt_rad : servo_.angleRad();
  servo_.step(want, dt);

  NavigatorInput input;
  input.time_s = sample.time_s;
  input.odometry = sample.odometry_pose;
  input.sonar = sonar_;
  const bool frame = sample.time_s + 1e-9 >= next_frame_s_;
  if (frame) {
    next_frame_s_ = sample.time_s + params_.camera_period_s;
    observation_ = observer_->observe(sample.true_pose.value_or(sample.odometry_pose),
                                      servo_.angleRad(), sample.time_s);
    input.observation = &observation_;
  }
  const NavigatorOutput out = navigator_.update(input);
  if (frame) {
    detections_.push_back({sample.time_s, servo_.angleRad(),
                           static_cast<int>(observation_.markers.size()),
                           static_cast<int>(observation_.lights.size()),
                           navStateName(navigator_.state()), out.target_body});
  }
  return out.command;
}

BehaviourStatus DeliveryBehaviour::status() const {
  BehaviourStatus s;
  s.phase = navStateName(navigator_.state());
  const auto n = navigator_.route().steps.size();
  s.finished = navigator_.arrived();
  s.progress = s.finished ? 1.0
                          : static_cast<double>(std::max(0, navigator_.nextStep() - 1)) /
                                static_cast<double>(std::max<std::size_t>(1, n - 1));
  if (!navigator_.events().empty())
    s.message = navigator_.events().back().note;
  return s;
}

}  // namespace irgs
