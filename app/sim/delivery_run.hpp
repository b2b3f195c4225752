#pragma once
// irgs-sim --behaviour deliver --from N --to M: a delivery run of paper 002 on the map's
// topological graph in the in-process simulator (core/scenario/delivery_scenario.hpp), and its
// outputs: the usual grid and trajectory (one row every 0.5 s), metrics.json with a "delivery"
// object, route.csv (the route and the action at each marker), detections.csv (one row per
// camera frame) and states.csv (the navigator's state changes).

#include <functional>

#include "app/sim/behaviour_run.hpp"
#include "app/sim/sim_options.hpp"

namespace irgs::app {

BehaviourRunOutcome runDeliveryMode(const SimOptions& options, const WorldMap& map,
                                    const RobotProfile& profile,
                                    const std::function<double()>& clock);

}  // namespace irgs::app
