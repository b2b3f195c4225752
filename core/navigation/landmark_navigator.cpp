#include "core/navigation/landmark_navigator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/motion/turn_control.hpp"

namespace irgs {

const char* navStateName(NavState state) {
  switch (state) {
    case NavState::kDepart:
      return "depart";
    case NavState::kFollowMarker:
      return "follow marker";
    case NavState::kTurnAtMarker:
      return "turn at marker";
    case NavState::kFollowLight:
      return "follow light";
    case NavState::kStraight:
      return "straight ahead";
    case NavState::kArrived:
      return "arrived";
  }
  return "?";
}

namespace {

double edgeHeading(const RoutePlan& route, std::size_t from) {
  const Vec2 d = route.steps[from + 1].position - route.steps[from].position;
  return std::atan2(d.y(), d.x());
}

}  // namespace

LandmarkNavigator::LandmarkNavigator(RoutePlan route, LandmarkNavigatorParams params)
    : route_(std::move(route)), params_(params) {
  if (route_.status != RouteStatus::kOk || route_.steps.empty())
    throw std::invalid_argument("LandmarkNavigator: the route is not a planned route");
  events_.push_back({0.0, NavState::kDepart, 0,
                     "route of " + std::to_string(route_.steps.size()) + " markers from node " +
                         route_.steps.front().node_id});
}

void LandmarkNavigator::enter(NavState state, double time_s, std::string note) {
  if (state == state_ && note.empty())
    return;
  state_ = state;
  events_.push_back({time_s, state, next_, std::move(note)});
}

double LandmarkNavigator::forwardSpeedLimit(std::span<const SonarRay> sonar) const {
  double nearest = std::numeric_limits<double>::infinity();
  for (const SonarRay& r : sonar) {
    if (std::abs(std::atan2(r.direction.y(), r.direction.x())) <= params_.front_cone_rad)
      nearest = std::min(nearest, r.range_m);
  }
  const double span = params_.front_slow_m - params_.front_stop_m;
  if (!std::isfinite(nearest) || !(span > 0.0))
    return 1.0;
  return std::clamp((nearest - params_.front_stop_m) / span, 0.0, 1.0);
}

void LandmarkNavigator::chooseTarget(const NavigatorInput& input) {
  const Pose2& odo = input.odometry;
  if (const CeilingObservation* obs = input.observation) {
    // Priority 1: the next route marker.
    std::optional<Vec2> best;
    double best_d = std::numeric_limits<double>::infinity();
    for (const MarkerDetection& m : obs->markers) {
      if (m.centre_body_m.x() < -0.3)
        continue;  // behind: already passed
      const Vec2 p = odo.toWorld(m.centre_body_m);
      if (consumed_ && (p - *consumed_).norm() < params_.consumed_radius_m)
        continue;
      if (params_.route_gate_m > 0.0 &&
          (p - route_.steps[static_cast<std::size_t>(next_)].position).norm() >
              params_.route_gate_m)
        continue;
      const double d = m.centre_body_m.norm();
      if (d < best_d) {
        best_d = d;
        best = p;
      }
    }
    if (best) {
      marker_ = best;
      marker_seen_s = input.time_s;
    }
    // Priority 2: the light farthest ahead whose tube runs along the travel direction.
    light_.reset();
    double farthest = -std::numeric_limits<double>::infinity();
    for (const LightDetection& l : obs->lights) {
      const Vec2& c = l.centre_body_m;
      if (c.x() <= 0.0 || std::abs(std::atan2(c.y(), c.x())) > params_.light_max_bearing_rad)
        continue;
      if (l.length_m > 0.2 &&
          std::abs(std::remainder(l.axis_rad, kPi)) > params_.light_axis_tolerance_rad)
        continue;
      if (c.x() > farthest) {
        farthest = c.x();
        light_ = odo.toWorld(c);
      }
    }
  }
  if (marker_ && input.time_s - marker_seen_s > params_.marker_memory_s)
    marker_.reset();
  if (marker_)
    enter(NavState::kFollowMarker, input.time_s, {});
  else if (light_)
    enter(NavState::kFollowLight, input.time_s, {});
  else
    enter(NavState::kStraight, input.time_s, {});
}

void LandmarkNavigator::actAtMarker(const NavigatorInput& input) {
  const RouteStep& step = route_.steps[static_cast<std::size_t>(next_)];
  consumed_ = input.odometry.position();
  marker_.reset();
  light_.reset();
  const std::string note = "marker of node " + step.node_id + ": " + markerActionName(step.action);
  if (step.action == MarkerAction::kStop) {
    enter(NavState::kArrived, input.time_s, note);
    return;
  }
  const std::size_t k = static_cast<std::size_t>(next_);
  ++next_;
  if (step.action == MarkerAction::kStraight) {
    enter(NavState::kFollowLight, input.time_s, note);
    return;
  }
  // Turn onto the outgoing edge. Its heading comes from the map (the odometry frame is the map
  // frame), so the turn also removes the approach angle the robot arrived with.
  turn_target_rad = edgeHeading(route_, k);
  enter(NavState::kTurnAtMarker, input.time_s, note);
}

NavigatorOutput LandmarkNavigator::update(const NavigatorInput& input) {
  NavigatorOutput out;
  out.tilt_rad = params_.tilt.min_tilt_rad;
  const Pose2& odo = input.odometry;
  if (state_ == NavState::kArrived) {
    last_ = out;
    return out;
  }
  if (state_ == NavState::kDepart) {
    if (route_.steps.size() == 1) {
      enter(NavState::kArrived, input.time_s, "start is the goal");
      last_ = out;
      return out;
    }
    const double heading = edgeHeading(route_, 0);
    if (!turnDone(odo.theta, heading, params_.turn_tolerance_rad)) {
      out.command = {0.0, turnRate(odo.theta, heading, params_.heading.max_turn_rate_radps)};
      out.wheels = wheelSpeedsFor(out.command.linear_mps, out.command.angular_radps,
                                  params_.wheel_separation_m);
      last_ = out;
      return out;
    }
    consumed_ = odo.position();
    next_ = 1;
    enter(NavState::kFollowLight, input.time_s, "left node " + route_.steps.front().node_id);
  }
  if (state_ == NavState::kTurnAtMarker) {
    if (!turnDone(odo.theta, turn_target_rad, params_.turn_tolerance_rad)) {
      out.command = {0.0,
                     turnRate(odo.theta, turn_target_rad, params_.heading.max_turn_rate_radps)};
      out.wheels = wheelSpeedsFor(out.command.linear_mps, out.command.angular_radps,
                                  params_.wheel_separation_m);
      out.tilt_rad = params_.tilt.max_tilt_rad;
      last_ = out;
      return out;
    }
    enter(NavState::kFollowLight, input.time_s, "turn done");
  }

  chooseTarget(input);
  double speed = params_.cruise_speed_mps;
  Vec2 target = Vec2::UnitX();
  if (state_ == NavState::kFollowMarker) {
    target = odo.toBody(*marker_);
    const double d = target.norm();
    out.tilt_rad = params_.tilt.tiltFor(d);
    const double rise = tiltRise(params_.tilt, out.tilt_rad);
    speed =
        params_.cruise_speed_mps - rise * (params_.cruise_speed_mps - params_.marker_min_speed_mps);
    if (d <= params_.overhead_radius_m || (target.x() <= 0.0 && d < 0.4)) {
      actAtMarker(input);
      out.command = {};
      out.wheels = {};
      out.tilt_rad = params_.tilt.max_tilt_rad;
      last_ = out;
      return out;
    }
  } else if (state_ == NavState::kFollowLight) {
    target = odo.toBody(*light_);
  }
  out.target_body = target.normalized() * params_.avoidance.target_gain;
  out.repulsive_body = repulsiveSum(params_.avoidance, input.sonar);
  out.move_body = moveVector(params_.avoidance, target, out.repulsive_body);
  out.command = trackMoveVector(params_.heading, out.move_body, speed);
  out.command.linear_mps *= forwardSpeedLimit(input.sonar);
  out.wheels =
      wheelSpeedsFor(out.command.linear_mps, out.command.angular_radps, params_.wheel_separation_m);
  last_ = out;
  return out;
}

}  // namespace irgs
