#pragma once
// Shared by the linked-robot tests: the bundled map and thesis robot, a FirmwareCore on them,
// and frames built through the real encoder/decoder.

#include <memory>
#include <stdexcept>
#include <string>

#include "app/robot/firmware_core.hpp"
#include "core/robot/robot_profile_file.hpp"
#include "core/sim/sim_presets.hpp"
#include "core/world/map_file.hpp"

namespace irgs::comms::testing {

inline RobotProfile thesisRobot() {
  auto loaded =
      loadRobotProfileFile(std::string(IRGS_SOURCE_DIR) + "/resources/robots/thesis_robot.json");
  if (!loaded.profile)
    throw std::runtime_error("cannot load the thesis robot profile");
  return *loaded.profile;
}

// A bundled robot profile by file name (resources/robots/NAME).
inline RobotProfile robotProfile(const std::string& name) {
  auto loaded = loadRobotProfileFile(std::string(IRGS_SOURCE_DIR) + "/resources/robots/" + name);
  if (!loaded.profile)
    throw std::runtime_error("cannot load the robot profile " + name);
  return *loaded.profile;
}

inline WorldMap defaultMap() {
  auto loaded = loadAnyMap(std::string(IRGS_SOURCE_DIR) + "/resources/maps/default.json");
  if (!loaded.map)
    throw std::runtime_error("cannot load the default map");
  return *loaded.map;
}

// The firmware on the default map with the thesis robot; ideal = no odometry or sensor noise.
inline std::unique_ptr<app::FirmwareCore> makeFirmware(app::FirmwareConfig config = {},
                                                       bool ideal = false, std::uint64_t seed = 7) {
  SimConfig sim;
  sim.seed = seed;
  sim = ideal ? idealSimConfig(sim) : typicalSimConfig(sim);
  return std::make_unique<app::FirmwareCore>(Simulator(defaultMap(), thesisRobot(), sim), config);
}

}  // namespace irgs::comms::testing
