#pragma once
// The navigation state machine of 002_… Fig. 18 (digest 3.8), pure and deterministic.
//
// Priority 1, a marker of the route in view: track only the marker, raising the camera as it
// comes closer (camera_tilt.hpp) and slowing down with the camera's rise (Fig. 20); when it is
// overhead perform the route's action for it (straight, left, right, stop). Priority 2, a light
// in view: follow the light farthest ahead. Priority 3, nothing: straight ahead. Always: the
// target direction plus the sonars' repulsive sum (avoidance.hpp) is the move vector, tracked by
// the heading controller (heading_controller.hpp).
//
// Marker identity comes from the route order (002_… 3.6 [A]): the marker sought is the next one
// on the route; one already acted on is ignored while the robot is near it, and (route_gate_m)
// a marker farther than the gate from where the map puts the next route node is not the one
// sought. Positions are kept in the odometry frame, which is the map frame when the run starts
// with the robot on the start node at the map's start pose (as irgs-sim does).

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/navigation/avoidance.hpp"
#include "core/navigation/camera_tilt.hpp"
#include "core/navigation/ceiling_observation.hpp"
#include "core/navigation/heading_controller.hpp"
#include "core/navigation/route_plan.hpp"

namespace irgs {

enum class NavState { kDepart, kFollowMarker, kTurnAtMarker, kFollowLight, kStraight, kArrived };
const char* navStateName(NavState state);

struct LandmarkNavigatorParams {
  TiltLaw tilt{.near_m = 0.3, .far_m = 3.0};  // deliveryParamsFor takes the profile's
  AvoidanceParams avoidance;
  HeadingControlParams heading;
  double wheel_separation_m = 0.4;  // B of A002-4, for the wheel speeds reported
  double cruise_speed_mps = 0.5;
  double marker_min_speed_mps = 0.12;     // with the camera straight up
  double overhead_radius_m = 0.08;        // the marker counts as overhead this close
  double consumed_radius_m = 1.5;         // a marker acted on is ignored this close to it
  double route_gate_m = 2.5;              // 0: accept any marker as the next one
  double marker_memory_s = 1.5;           // a tracked marker out of view is followed this long
  double light_max_bearing_rad = 0.7;     // lights farther off the forward axis are not targets
  double light_axis_tolerance_rad = 0.6;  // ... nor lights whose tube crosses the travel direction
  double front_stop_m = 0.3;              // forward speed is 0 with an echo this close ahead
  double front_slow_m = 0.9;              // ... and full beyond this
  double front_cone_rad = 0.7;            // sonars within this of forward limit the speed
  double turn_tolerance_rad = 0.03;
};

struct NavigatorInput {
  double time_s = 0.0;
  Pose2 odometry;
  const CeilingObservation* observation = nullptr;  // a new camera frame, or null
  std::span<const SonarRay> sonar;                  // latest reading of every sonar, body frame
};

struct NavigatorOutput {
  VelocityCommand command;
  WheelCommand wheels;    // eq. (14) for the command
  double tilt_rad = 0.0;  // where the camera should look
  Vec2 target_body = Vec2::Zero();
  Vec2 repulsive_body = Vec2::Zero();
  Vec2 move_body = Vec2::Zero();
};

struct NavEvent {
  double time_s = 0.0;
  NavState state = NavState::kDepart;
  int route_index = 0;  // the route step sought (or acted on, for a marker action)
  std::string note;
};

class LandmarkNavigator {
 public:
  // Throws std::invalid_argument for a route that is not kOk or has no steps.
  LandmarkNavigator(RoutePlan route, LandmarkNavigatorParams params);

  NavigatorOutput update(const NavigatorInput& input);

  NavState state() const { return state_; }
  bool arrived() const { return state_ == NavState::kArrived; }
  // Index of the route step whose marker is sought next.
  int nextStep() const { return next_; }
  const RoutePlan& route() const { return route_; }
  const LandmarkNavigatorParams& params() const { return params_; }
  const std::vector<NavEvent>& events() const { return events_; }
  const NavigatorOutput& lastOutput() const { return last_; }

 private:
  void enter(NavState state, double time_s, std::string note);
  void chooseTarget(const NavigatorInput& input);
  void actAtMarker(const NavigatorInput& input);
  double forwardSpeedLimit(std::span<const SonarRay> sonar) const;

  RoutePlan route_;
  LandmarkNavigatorParams params_;
  NavState state_ = NavState::kDepart;
  int next_ = 0;
  std::optional<Vec2> consumed_;  // odometry position where the last marker was acted on
  std::optional<Vec2> marker_;    // tracked marker, odometry frame
  double marker_seen_s = 0.0;
  std::optional<Vec2> light_;  // light target, odometry frame
  double turn_target_rad = 0.0;
  std::vector<NavEvent> events_;
  NavigatorOutput last_;
};

}  // namespace irgs
