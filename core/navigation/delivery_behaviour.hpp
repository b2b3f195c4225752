#pragma once
// The delivery behaviour of 002_…: the landmark navigator (landmark_navigator.hpp) fed by a
// ceiling camera (any CeilingObserver) and the robot's sonars, behind the Behaviour interface,
// so the same object drives the simulator, irgs-sim --behaviour deliver and the GUI.
//
// The camera takes a frame every camera_period_s at the tilt the navigator asked for one frame
// earlier (the servo follows at tilt_rate_radps). A simulated observer is given the sample's
// true pose (the simulator's ground truth); a real camera ignores it.

#include <memory>
#include <string>
#include <vector>

#include "core/behaviour/behaviour.hpp"
#include "core/camera/tilt_servo.hpp"
#include "core/navigation/landmark_navigator.hpp"
#include "core/robot/robot_profile.hpp"

namespace irgs {

struct DeliveryParams {
  LandmarkNavigatorParams navigator;
  double camera_period_s = 0.1;
  double tilt_rate_radps = 1.5;  // the tilt servo's speed
};

// Defaults fitted to a robot profile: the wheel separation, forward and turn speed, and the
// tilt law and servo rate of its "ceiling_camera" (defaults when it has none).
DeliveryParams deliveryParamsFor(const RobotProfile& profile);

// One camera frame as the behaviour used it.
struct DetectionRecord {
  double time_s = 0.0;
  double tilt_rad = 0.0;
  int markers = 0;
  int lights = 0;
  std::string state;  // navigator state after the frame
  Vec2 target_body = Vec2::Zero();
};

class DeliveryBehaviour final : public Behaviour {
 public:
  DeliveryBehaviour(RoutePlan route, const RobotProfile& profile,
                    std::shared_ptr<CeilingObserver> observer, DeliveryParams params);

  VelocityCommand onSample(const TelemetrySample& sample) override;
  BehaviourStatus status() const override;
  std::string_view name() const override { return "deliver"; }

  const LandmarkNavigator& navigator() const { return navigator_; }
  const CeilingObservation& lastObservation() const { return observation_; }
  const std::vector<DetectionRecord>& detections() const { return detections_; }
  double tilt_rad() const { return servo_.angleRad(); }

 private:
  LandmarkNavigator navigator_;
  std::shared_ptr<CeilingObserver> observer_;
  DeliveryParams params_;
  std::vector<SonarRay> sonar_;
  std::vector<double> max_range_;
  CeilingObservation observation_;
  std::vector<DetectionRecord> detections_;
  double next_frame_s_ = 0.0;
  TiltServo servo_;
  double last_time_s_ = 0.0;
};

}  // namespace irgs
