#pragma once
// Shared loading for the behaviour tests: bundled maps and the thesis robot.

#include <gtest/gtest.h>

#include <string>

#include "core/robot/robot_profile_file.hpp"
#include "core/world/map_file.hpp"

namespace irgs::test {

inline WorldMap loadBundledMap(const std::string& name) {
  auto loaded = loadAnyMap(std::string(IRGS_SOURCE_DIR) + "/resources/maps/" + name + ".json");
  if (!loaded.map)
    throw std::runtime_error("cannot load map " + name);
  return *loaded.map;
}

inline RobotProfile thesisRobot() {
  auto loaded =
      loadRobotProfileFile(std::string(IRGS_SOURCE_DIR) + "/resources/robots/thesis_robot.json");
  if (!loaded.profile)
    throw std::runtime_error("cannot load the thesis robot");
  return *loaded.profile;
}

}  // namespace irgs::test
