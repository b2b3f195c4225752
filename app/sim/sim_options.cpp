#include "app/sim/sim_options.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <sstream>

#include "core/estimation/estimator_runner.hpp"

namespace irgs::app {
namespace {

std::optional<double> parseDouble(const std::string& text) {
  double value = 0.0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (ec != std::errc{} || ptr != end || !std::isfinite(value))
    return std::nullopt;
  return value;
}

std::optional<Pose2> parseStart(const std::string& text) {
  std::vector<double> values;
  std::stringstream stream(text);
  std::string item;
  while (std::getline(stream, item, ',')) {
    const auto v = parseDouble(item);
    if (!v)
      return std::nullopt;
    values.push_back(*v);
  }
  if (values.size() != 3)
    return std::nullopt;
  return Pose2{values[0], values[1], wrapAngle(degToRad(values[2]))};
}

}  // namespace

std::string simUsage() {
  return R"(usage: irgs-sim --map FILE --out DIR [options]
       irgs-sim --connect URL --out DIR [--script FILE] [options]

Runs a scenario headless: the simulated robot drives a timed command script on a map while the
live sonar grid is built, then writes the results.

  --map FILE        JSON map (resources/maps/*.json) or ROS map_server YAML (required)
  --out DIR         output folder, created if missing (required)
  --robot FILE      robot profile JSON (default: the bundled thesis robot)
  --start X,Y,TH    start pose in metres and degrees (default: the map's start pose)
  --script FILE     timed drive script (default: none, the robot stands still)
  --seed N          random seed for odometry and sensor noise (default: 1)
  --duration S      simulated seconds (default: the script's length, or 60 without a script)
  --resolution M    grid cell size in metres (default: 0.01)
  --ideal           no odometry error and no sensor noise
  --quiet           print nothing on success
  --connect URL     run on a robot behind a link instead of the simulator: MAVLink
                    (serial:///dev/ttyUSB0?baud=115200, tcp://host:5760, udp://:14550) or
                    ARCOS/P2OS with ?protocol=arcos (a Pioneer, MobileSim/AMRISim on
                    tcp://localhost:8101?protocol=arcos, irgs-robot --protocol arcos). The script
                    or --behaviour runs on the wall clock, the robot is stopped at the end and on
                    Ctrl-C. --map is optional (its name is recorded; with --behaviour mapbuild
                    the built map is scored against it; goal and coverage plan on it); --start
                    (default: the --map's start pose) says where the robot stands in the map
                    frame when the run begins: the odometry is re-expressed so that its first
                    sample lies there; without --map and --start the odometry is used as it
                    comes. --ideal is refused. Also writes link.json (protocol, link statistics;
                    no ground truth: the true_* columns repeat the odometry, the odometry error
                    is null)
  --connect-timeout S  seconds to wait for the robot's heartbeat and first odometry (10)
  --signing-key FILE  with a MAVLink --connect: MAVLink 2 signing with the key in FILE (64 hex
                    digits, as the GUI's connection dialog exports it and irgs-robot
                    --signing-key reads it); a robot with a key refuses unsigned commands
  --behaviour B     a behaviour drives the robot instead of a script: mapbuild (autonomous
                    sonar map building: wall following, loop closing, interior, obstacles),
                    goal (A* on the map, path amendment, traveling in 15-degree turns; needs
                    --goal) or coverage (spiral cleaning path). --duration is the time budget
                    (default 3600). Also writes indices.csv (mapbuild: position indices) or
                    plan.csv (the planned turning points); metrics.json gains a "behaviour"
                    object (phases with times, turns, wall clock) and map_score (F1 of the
                    built map against the true map), plan or coverage
                    deliver: landmark navigation of paper 002 (A* on the map's topological
                    graph from --from to --to, ceiling markers and lights through the
                    --observer camera, sonar avoidance); writes route.csv, detections.csv,
                    states.csv, trajectory.csv every 0.5 s and metrics.json with a
                    "delivery" object (success, time, distance, min clearance, collisions)
  --from N, --to N  start and goal node (id, or index in the graph) for --behaviour deliver;
                    the robot starts on the start node facing the map's start heading
  --observer O      what sees the ceiling for deliver: ideal (geometric projection of the
                    map's markers and lights with seeded noise; default) or vision (frames
                    rendered by the simulated ceiling camera of the robot profile, through the
                    OpenCV marker and light pipelines)
  --goal X,Y        goal position in metres for --behaviour goal
  --compare FILE    with --behaviour mapbuild: also score the built map against a map an
                    earlier run saved (its grid.yaml), e.g. the in-process run of the same
                    scenario against the linked one: map_agreement (precision, recall, F1 with
                    the same 2-cell tolerance) in metrics.json
  --route X,Y;X,Y   waypoints (metres) the robot drives in order for --localize ('/' may
                    separate the points instead of ';')
  --localize E      localization experiment with estimator E: ekf (stereo-sonar EKF of paper
                    000 on the map's walls, corners and edges), dr (encoder dead reckoning) or
                    encoder-gyro (paper 001 feedback filter, AUTOGYRO-level gyro) or mouse
                    (paper 004 two-sensor optical-mouse odometry; needs a robot with
                    drive/mouse_sensors, e.g. --robot resources/robots/mouse_type20_004.json)
                    or ekf-caster (the 000 EKF on its three-caster robot: least-squares J+
                    odometry from the six caster encoders with adaptive process noise
                    lambda ||e||; needs --robot resources/robots/caster3_000.json). The robot
                    drives the map's route graph (nodes in order, back to the first) at
                    0.3 m/s, or --route, or --script. Writes localization_metrics.json (RMS, max and final
                    errors of the estimate and of dead reckoning, NEES, accepted measurements)
                    and localization.csv (truth, estimate, DR, errors, 1-sigma, NEES per 0.1 s)
  --caster-lambda L with --localize ekf-caster: the adaptive process-noise scale lambda of
                    Q = lambda ||e|| I6 (default 0.005, paper 000)
  --help            this text

Outputs: grid.pgm + grid.yaml (ROS map_server), grid.png (grid with the true path in blue and
the odometry path in orange), metrics.json, trajectory.csv.
Exit status: 0 success, 1 a file could not be read or written, 2 bad arguments, 3 the linked
robot never came up (--connect) or the behaviour failed (--behaviour: budget used up, goal
unreachable; outputs written when the run took place), 130 interrupted (outputs written for
what was run).
)";
}

SimOptionsResult parseSimOptions(const std::vector<std::string>& args) {
  SimOptions options;
  auto fail = [](std::string message) { return SimOptionsResult{std::nullopt, false, message}; };

  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    if (arg == "--help" || arg == "-h")
      return {std::nullopt, true, {}};
    if (arg == "--ideal") {
      options.ideal = true;
      continue;
    }
    if (arg == "--quiet") {
      options.quiet = true;
      continue;
    }
    if (arg.rfind("--", 0) != 0)
      return fail("unexpected argument '" + arg + "'");
    if (i + 1 >= args.size())
      return fail(arg + " needs a value");
    const std::string& value = args[++i];

    if (arg == "--map") {
      options.map = value;
    } else if (arg == "--out") {
      options.out = value;
    } else if (arg == "--robot") {
      options.robot = value;
    } else if (arg == "--script") {
      options.script = value;
    } else if (arg == "--start") {
      options.start = parseStart(value);
      if (!options.start)
        return fail("--start wants X,Y,THETA_DEG (e.g. 1.0,0.5,90), got '" + value + "'");
    } else if (arg == "--seed") {
      std::uint64_t seed = 0;
      const auto [ptr, ec] = std::from_chars(value.data(), value.data() + value.size(), seed);
      if (ec != std::errc{} || ptr != value.data() + value.size()) {
        return fail("--seed wants a non-negative integer, got '" + value + "'");
      }
      options.seed = seed;
    } else if (arg == "--duration") {
      const auto d = parseDouble(value);
      if (!d || *d <= 0.0 || *d > 1.0e6)
        return fail("--duration wants seconds in (0, 1e6], got '" + value + "'");
      options.duration_s = *d;
    } else if (arg == "--connect") {
      if (value.find("://") == std::string::npos)
        return fail("--connect wants a URL such as serial:///dev/ttyUSB0?baud=115200, got '" +
                    value + "'");
      options.connect = value;
    } else if (arg == "--behaviour") {
      if (value != "mapbuild" && value != "goal" && value != "coverage" && value != "deliver")
        return fail("--behaviour wants mapbuild, goal, coverage or deliver, got '" + value + "'");
      options.behaviour = value;
    } else if (arg == "--from") {
      options.from_node = value;
    } else if (arg == "--to") {
      options.to_node = value;
    } else if (arg == "--observer") {
      if (value != "ideal" && value != "vision")
        return fail("--observer wants ideal or vision, got '" + value + "'");
      options.observer = value;
    } else if (arg == "--localize") {
      if (!parseEstimatorKind(value))
        return fail("--localize wants ekf, dr, encoder-gyro, mouse or ekf-caster, got '" + value +
                    "'");
      options.localize = value;
    } else if (arg == "--caster-lambda") {
      const auto l = parseDouble(value);
      if (!l || *l < 0.0 || *l > 1e6)
        return fail("--caster-lambda wants a number >= 0 (paper 000: 0.005), got '" + value + "'");
      options.caster_lambda = *l;
    } else if (arg == "--route") {
      std::string list = value;  // ';' or '/' between points ('/' needs no shell quoting)
      std::replace(list.begin(), list.end(), '/', ';');
      std::stringstream points(list);
      std::string point;
      options.route.clear();
      while (std::getline(points, point, ';')) {
        const auto comma = point.find(',');
        const auto x = parseDouble(point.substr(0, comma));
        const auto y =
            comma == std::string::npos ? std::nullopt : parseDouble(point.substr(comma + 1));
        if (!x || !y)
          return fail("--route wants X,Y;X,Y;... in metres (e.g. '15.9,0.775;15.9,-14.55'), got '" +
                      value + "'");
        options.route.emplace_back(*x, *y);
      }
      if (options.route.empty())
        return fail("--route needs at least one X,Y waypoint");
    } else if (arg == "--compare") {
      if (value.empty())
        return fail("--compare needs a map YAML file (grid.yaml of an earlier run)");
      options.compare = value;
    } else if (arg == "--goal") {
      const auto comma = value.find(',');
      const auto x = parseDouble(value.substr(0, comma));
      const auto y =
          comma == std::string::npos ? std::nullopt : parseDouble(value.substr(comma + 1));
      if (!x || !y)
        return fail("--goal wants X,Y in metres (e.g. 4.5,2.0), got '" + value + "'");
      options.goal = Vec2(*x, *y);
    } else if (arg == "--signing-key") {
      if (value.empty())
        return fail("--signing-key needs a key file (64 hex digits)");
      options.signing_key = value;
    } else if (arg == "--connect-timeout") {
      const auto t = parseDouble(value);
      if (!t || *t <= 0.0 || *t > 3600.0)
        return fail("--connect-timeout wants seconds in (0, 3600], got '" + value + "'");
      options.connect_timeout_s = *t;
    } else if (arg == "--resolution") {
      const auto r = parseDouble(value);
      if (!r || *r < 0.005 || *r > 1.0)
        return fail("--resolution wants metres in [0.005, 1], got '" + value + "'");
      options.grid_resolution_m = *r;
    } else {
      return fail("unknown option '" + arg + "' (see --help)");
    }
  }
  if (!options.connect.empty()) {
    // A real robot's sensors are its own: nothing to idealise. (--start only says where it is.)
    if (options.ideal)
      return fail("--ideal has no meaning for a linked robot (--connect)");
  } else if (options.map.empty()) {
    return fail("--map FILE is required (see --help)");
  } else if (!options.signing_key.empty()) {
    return fail("--signing-key signs a link: it needs --connect");
  }
  if (!options.behaviour.empty()) {
    if (!options.script.empty())
      return fail("--behaviour drives the robot itself; it cannot be combined with --script");
    if (options.behaviour == "goal" && !options.goal)
      return fail("--behaviour goal needs --goal X,Y");
    if (options.behaviour == "deliver" && (options.from_node.empty() || options.to_node.empty()))
      return fail("--behaviour deliver needs --from NODE and --to NODE");
    if (options.behaviour == "deliver" && !options.connect.empty())
      return fail(
          "--behaviour deliver sees the ceiling through the simulated camera; it "
          "cannot be combined with --connect");
  }
  if ((!options.from_node.empty() || !options.to_node.empty()) && options.behaviour != "deliver")
    return fail("--from and --to are only used with --behaviour deliver");
  if (!options.localize.empty() && (!options.connect.empty() || !options.behaviour.empty()))
    return fail(
        "--localize runs its own route in the simulator; it cannot be combined with "
        "--connect or --behaviour");
  if (options.caster_lambda && options.localize != "ekf-caster")
    return fail("--caster-lambda is only used with --localize ekf-caster");
  if (!options.route.empty() && options.localize.empty())
    return fail("--route is only used with --localize");
  if (!options.route.empty() && !options.script.empty())
    return fail("--route and --script both drive the robot: give one");
  if (!options.compare.empty() && options.behaviour != "mapbuild")
    return fail("--compare is only used with --behaviour mapbuild");
  if (options.goal && options.behaviour != "goal")
    return fail("--goal is only used with --behaviour goal");
  if (options.out.empty())
    return fail("--out DIR is required (see --help)");
  return {options, false, {}};
}

}  // namespace irgs::app
