#include "app/sim/delivery_run.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "core/camera/ceiling_camera_config.hpp"
#include "core/camera/ceiling_scene.hpp"
#include "core/io/atomic_file.hpp"
#include "core/scenario/delivery_scenario.hpp"
#include "core/scenario/scenario_outputs.hpp"
#include "core/sim/sim_presets.hpp"
#include "core/vision/vision_ceiling_observer.hpp"

namespace irgs::app {
namespace {

constexpr int kExitFiles = 1;
constexpr int kExitBehaviourFailed = 3;

double rounded(double v, int digits = 4) {
  const double f = std::pow(10.0, digits);
  return std::round(v * f) / f;
}

std::string routeCsv(const RoutePlan& route) {
  std::ostringstream out;
  out << "index,node,x_m,y_m,action,turn_deg\n";
  char line[160];
  for (std::size_t i = 0; i < route.steps.size(); ++i) {
    const RouteStep& s = route.steps[i];
    std::snprintf(line, sizeof line, "%zu,%s,%.3f,%.3f,%s,%.1f\n", i, s.node_id.c_str(),
                  s.position.x(), s.position.y(), markerActionName(s.action), radToDeg(s.turn_rad));
    out << line;
  }
  return out.str();
}

std::string detectionsCsv(const std::vector<DetectionRecord>& records) {
  std::ostringstream out;
  out << "time_s,tilt_deg,markers,lights,state,target_x,target_y\n";
  char line[160];
  for (const DetectionRecord& r : records) {
    std::snprintf(line, sizeof line, "%.2f,%.1f,%d,%d,%s,%.3f,%.3f\n", r.time_s,
                  radToDeg(r.tilt_rad), r.markers, r.lights, r.state.c_str(), r.target_body.x(),
                  r.target_body.y());
    out << line;
  }
  return out.str();
}

std::string statesCsv(const std::vector<NavEvent>& events) {
  std::ostringstream out;
  out << "time_s,state,route_index,note\n";
  char line[256];
  for (const NavEvent& e : events) {
    std::snprintf(line, sizeof line, "%.2f,%s,%d,\"%s\"\n", e.time_s, navStateName(e.state),
                  e.route_index, e.note.c_str());
    out << line;
  }
  return out.str();
}

}  // namespace

BehaviourRunOutcome runDeliveryMode(const SimOptions& options, const WorldMap& map,
                                    const RobotProfile& profile,
                                    const std::function<double()>& clock) {
  BehaviourRunOutcome outcome;
  DeliveryScenarioSpec spec;
  spec.map = map;
  spec.profile = profile;
  spec.from_node = options.from_node;
  spec.to_node = options.to_node;
  spec.sim = options.ideal ? idealSimConfig() : typicalSimConfig();
  spec.sim.seed = options.seed;
  spec.max_duration_s = options.duration_s.value_or(300.0);
  spec.wall_clock = clock;
  if (options.observer == "vision") {
    // The frames are rendered at the true pose and go through the OpenCV pipelines; the
    // robot profile's ceiling_camera (or the default camera) says what the camera is.
    const CeilingCameraConfigResult camera = ceilingCameraFromProfile(profile);
    if (!camera.errors.empty()) {
      outcome.exit_code = kExitBehaviourFailed;
      outcome.error = "robot profile ceiling_camera: " + camera.errors.front();
      return outcome;
    }
    RenderSettings render;
    render.seed = options.seed;
    spec.observer = std::make_shared<vision::VisionCeilingObserver>(
        sceneFromMap(map), camera.config, vision::VisionConfig{}, render);
  }
  DeliveryScenarioResult result = runDeliveryScenario(spec);
  if (!result.error.empty()) {
    outcome.exit_code = kExitBehaviourFailed;
    outcome.error = result.error;
    return outcome;
  }
  const ScenarioRunInfo info{options.map.filename().string(), profile.name, options.seed};
  const WriteOutputsResult written = writeScenarioOutputs(result.run.scenario, info, options.out);
  outcome.written = written.written;
  if (!written.error.empty()) {
    outcome.exit_code = kExitFiles;
    outcome.error = written.error;
    return outcome;
  }
  const DeliveryMetrics& d = result.delivery;
  nlohmann::json route = nlohmann::json::array();
  for (const RouteStep& s : result.route.steps)
    route.push_back({{"node", s.node_id}, {"action", markerActionName(s.action)}});
  nlohmann::json extra;
  extra["delivery"] = {{"from", result.route.steps.front().node_id},
                       {"to", result.route.steps.back().node_id},
                       {"observer", options.observer},
                       {"route", route},
                       {"route_length_m", rounded(result.route.length_m)},
                       {"success", d.success},
                       {"arrived", d.arrived},
                       {"time_s", rounded(d.time_s, 2)},
                       {"distance_m", rounded(d.distance_m, 3)},
                       {"goal_error_m", rounded(d.goal_error_m, 3)},
                       {"min_clearance_m", rounded(d.min_clearance_m, 3)},
                       {"collisions", d.collisions},
                       {"markers_acted", d.markers_acted},
                       {"moving_obstacles", map.moving_obstacles.size()}};
  const auto write = [&](const std::string& name, const std::string& text) {
    const auto path = options.out / name;
    if (const auto err = writeFileAtomically(path, text)) {
      outcome.exit_code = kExitFiles;
      outcome.error = *err;
      return false;
    }
    if (std::find(outcome.written.begin(), outcome.written.end(), path) == outcome.written.end())
      outcome.written.push_back(path);
    return true;
  };
  if (!write("metrics.json", behaviourMetricsJson(result.run, info, extra)) ||
      !write("route.csv", routeCsv(result.route)) ||
      !write("detections.csv", detectionsCsv(result.detections)) ||
      !write("states.csv", statesCsv(result.events)))
    return outcome;
  char line[320];
  std::snprintf(line, sizeof line,
                "deliver %s -> %s %s after %.1f s, %.2f m, goal error %.3f m, min clearance "
                "%.3f m, %d collisions",
                result.route.steps.front().node_id.c_str(),
                result.route.steps.back().node_id.c_str(), d.success ? "succeeded" : "FAILED",
                d.time_s, d.distance_m, d.goal_error_m, d.min_clearance_m, d.collisions);
  outcome.summary = line;
  if (!d.success)
    outcome.exit_code = kExitBehaviourFailed;
  return outcome;
}

}  // namespace irgs::app
