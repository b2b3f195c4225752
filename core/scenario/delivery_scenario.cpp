#include "core/scenario/delivery_scenario.hpp"

#include <algorithm>
#include <limits>

#include "core/sim/body_clearance.hpp"

namespace irgs {

namespace {
constexpr double kClearanceCap_m = 2.0;
constexpr double kContact_m = 0.003;  // closer than this counts as touching
}  // namespace

DeliveryScenarioResult runDeliveryScenario(const DeliveryScenarioSpec& spec) {
  DeliveryScenarioResult out;
  const std::string from = resolveNodeId(spec.map.graph, spec.from_node);
  const std::string to = resolveNodeId(spec.map.graph, spec.to_node);
  if (from.empty() || to.empty()) {
    out.error = "unknown node '" + (from.empty() ? spec.from_node : spec.to_node) + "'";
    return out;
  }
  out.route = planRoute(spec.map.graph, from, to);
  if (out.route.status != RouteStatus::kOk) {
    out.error = std::string("no route from node ") + from + " to node " + to + ": " +
                routeStatusName(out.route.status);
    return out;
  }
  std::shared_ptr<CeilingObserver> observer = spec.observer;
  if (!observer)
    observer = std::make_shared<IdealCeilingObserver>(spec.map, spec.camera, spec.sim.seed);
  DeliveryBehaviour behaviour(out.route, spec.profile, observer, deliveryParamsFor(spec.profile));

  BehaviourScenarioSpec run;
  run.map = spec.map;
  run.profile = spec.profile;
  run.start = Pose2{out.route.steps.front().position.x(), out.route.steps.front().position.y(),
                    spec.map.start.theta};
  run.sim = spec.sim;
  run.max_duration_s = spec.max_duration_s;
  run.trajectory_period_s = spec.trajectory_period_s;
  run.grid_resolution_m = 0.05;
  run.wall_clock = spec.wall_clock;
  double min_clearance = std::numeric_limits<double>::infinity();
  int collisions = 0;
  bool touching = false;
  std::vector<Vec2> body(spec.profile.body_outline.size());
  run.simulator_probe = [&](const Simulator& sim) {
    const Pose2& pose = sim.truePose();
    for (std::size_t i = 0; i < body.size(); ++i)
      body[i] = pose.toWorld(spec.profile.body_outline[i]);
    const double c = bodyClearance(sim.world(), body, kClearanceCap_m);
    min_clearance = std::min(min_clearance, c);
    const bool touch = c <= kContact_m;
    if (touch && !touching)
      ++collisions;
    touching = touch;
  };
  out.run = runBehaviourScenario(run, behaviour);

  DeliveryMetrics& d = out.delivery;
  d.arrived = behaviour.navigator().arrived();
  d.time_s = out.run.scenario.metrics.duration_s;
  d.distance_m = out.run.scenario.metrics.distance_travelled_m;
  d.goal_error_m =
      (out.run.scenario.metrics.final_truth.position() - out.route.steps.back().position).norm();
  d.min_clearance_m = std::isfinite(min_clearance) ? min_clearance : kClearanceCap_m;
  d.collisions = collisions;
  for (const NavEvent& e : behaviour.navigator().events())
    d.markers_acted += e.note.rfind("marker of node", 0) == 0 ? 1 : 0;
  d.success = d.arrived && d.goal_error_m <= spec.success_radius_m && d.collisions == 0;
  out.detections = behaviour.detections();
  out.events = behaviour.navigator().events();
  return out;
}

}  // namespace irgs
