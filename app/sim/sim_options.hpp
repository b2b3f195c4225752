#pragma once
// Command line of irgs-sim, parsed into a plain value.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/geometry/types.hpp"

namespace irgs::app {

struct SimOptions {
  std::filesystem::path map;
  std::filesystem::path robot;  // empty: the bundled thesis robot
  std::optional<Pose2> start;   // theta given in degrees on the command line
  std::filesystem::path script;
  std::uint64_t seed = 1;
  std::optional<double> duration_s;  // default: the script's length, or 60 s without a script
  std::filesystem::path out;
  double grid_resolution_m = 0.01;
  bool ideal = false;  // no odometry error and no sensor noise
  bool quiet = false;
  // --connect URL: drive a robot behind a link (MAVLink, or ARCOS with ?protocol=arcos) instead
  // of the in-process simulator. With --connect, --start (default: the --map's start pose) is
  // where the robot stands in the map frame when the run begins: its odometry is re-expressed
  // so that the first sample lies there (app/sim/linked_run.hpp).
  std::string connect;
  double connect_timeout_s = 10.0;  // --connect-timeout: link up and first sample
  // --signing-key FILE (with a MAVLink --connect): sign what is sent, accept only what is signed
  // with the key (comms/mavlink/signing_key.hpp has the file format).
  std::filesystem::path signing_key;
  // --behaviour mapbuild|goal|coverage: a host behaviour drives the simulated robot instead of
  // a script (app/sim/behaviour_run.hpp); --goal X,Y (metres) for "goal".
  std::string behaviour;
  std::optional<Vec2> goal;
  // --compare FILE: a map saved by an earlier run (grid.yaml); mapbuild scores its built map
  // against it too (map_agreement in metrics.json, app/sim/map_compare.hpp).
  std::filesystem::path compare;
  // --localize ekf|dr|encoder-gyro|mouse|ekf-caster: a localization experiment
  // (app/sim/localization_run.hpp).
  std::string localize;
  std::optional<double> caster_lambda;  // --caster-lambda: Q = lambda ||e|| (ekf-caster)
  // --behaviour deliver: landmark navigation of 002_… on the map's topological graph from node
  // --from to node --to (app/sim/delivery_run.hpp); --observer says what sees the ceiling.
  std::string from_node;
  std::string to_node;
  std::string observer = "ideal";
  std::vector<Vec2> route;  // --route X,Y;X,Y;...: waypoints for --localize (default: map graph)
};

struct SimOptionsResult {
  std::optional<SimOptions> options;
  bool help = false;
  std::string error;  // set when options is empty and help is false
};

SimOptionsResult parseSimOptions(const std::vector<std::string>& args);
std::string simUsage();

}  // namespace irgs::app
