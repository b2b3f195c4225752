#pragma once
// A headless delivery run (002_…): the delivery behaviour (core/navigation) drives the
// simulator from one topological node to another; the run measures what the paper's Figs. 23
// and 24 show (the path, one point every 0.5 s) and what an acceptance test needs: success,
// time, distance, the body's smallest clearance to anything and the number of contacts.

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/navigation/delivery_behaviour.hpp"
#include "core/navigation/ideal_ceiling_observer.hpp"
#include "core/scenario/behaviour_runner.hpp"

namespace irgs {

struct DeliveryScenarioSpec {
  WorldMap map;
  RobotProfile profile;
  std::string from_node;  // node ids (resolveNodeId: an index works too)
  std::string to_node;
  SimConfig sim;
  double max_duration_s = 300.0;
  double trajectory_period_s = 0.5;
  double success_radius_m = 0.5;  // the run succeeds when it stops this close to the goal node
  // What sees the ceiling. Null: an IdealCeilingObserver with `camera`, seeded from sim.seed.
  std::shared_ptr<CeilingObserver> observer;
  IdealCameraParams camera;
  std::function<double()> wall_clock;
};

struct DeliveryMetrics {
  bool arrived = false;  // the navigator performed the goal marker's stop
  bool success = false;  // arrived, within success_radius_m of the goal node, no collision
  double time_s = 0.0;
  double distance_m = 0.0;
  double goal_error_m = 0.0;     // true final position to the goal node
  double min_clearance_m = 0.0;  // body outline to the nearest geometry, over the run
  int collisions = 0;            // times the body came into contact (rising edges)
  int markers_acted = 0;
};

struct DeliveryScenarioResult {
  std::string error;  // set when the run could not start (unknown node, no route)
  RoutePlan route;
  BehaviourScenarioResult run;
  DeliveryMetrics delivery;
  std::vector<DetectionRecord> detections;
  std::vector<NavEvent> events;
};

// Throws what Simulator throws for a profile or config it cannot run.
DeliveryScenarioResult runDeliveryScenario(const DeliveryScenarioSpec& spec);

}  // namespace irgs
