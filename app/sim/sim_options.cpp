#include "app/sim/sim_options.hpp"

#include <charconv>
#include <cmath>
#include <sstream>

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
  --help            this text

Outputs: grid.pgm + grid.yaml (ROS map_server), grid.png (grid with the true path in blue and
the odometry path in orange), metrics.json, trajectory.csv.
Exit status: 0 success, 1 a file could not be read or written, 2 bad arguments.
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
    } else if (arg == "--resolution") {
      const auto r = parseDouble(value);
      if (!r || *r < 0.005 || *r > 1.0)
        return fail("--resolution wants metres in [0.005, 1], got '" + value + "'");
      options.grid_resolution_m = *r;
    } else {
      return fail("unknown option '" + arg + "' (see --help)");
    }
  }
  if (options.map.empty())
    return fail("--map FILE is required (see --help)");
  if (options.out.empty())
    return fail("--out DIR is required (see --help)");
  return {options, false, {}};
}

}  // namespace irgs::app
