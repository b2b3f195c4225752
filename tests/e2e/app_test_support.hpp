#pragma once
// Shared helpers for the offscreen application tests: one QApplication for the process, a small
// room, the bundled robot and a simulated-robot factory.

#include <QApplication>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include "app/gui/gamepad_source.hpp"
#include "app/gui/session_controller.hpp"
#include "core/robot/robot_profile_file.hpp"
#include "core/sim/simulated_robot.hpp"
#include "core/world/world_map.hpp"

namespace irgs::gui::test {

// No gamepad, and none to come: for a DriveInputController that only needs its pad.
class NoGamepad : public GamepadSource {
 public:
  std::optional<GamepadState> poll() override { return std::nullopt; }
  std::string deviceName() const override { return {}; }
  std::string unavailableReason() const override { return {}; }
};

// The offscreen platform needs no display; set before the application exists.
inline QApplication& ensureApp() {
  if (auto* app = qobject_cast<QApplication*>(QCoreApplication::instance()))
    return *app;
  if (qEnvironmentVariableIsEmpty("QT_QPA_PLATFORM"))
    qputenv("QT_QPA_PLATFORM", "offscreen");
  static int argc = 1;
  static char name[] = "app_gui_test";
  static char* argv[] = {name, nullptr};
  // Never destroyed: a QApplication torn down by exit handlers, after Qt's own statics, crashes.
  static auto* app = new QApplication(argc, argv);
  return *app;
}

// A closed square room of side 2 * half_m centred on the origin; the robot starts at the
// centre facing +x.
inline WorldMap squareRoom(double half_m = 1.5) {
  WorldMap map;
  map.name = "test room";
  Wall wall;
  wall.id = "room";
  wall.points = {Vec2(-half_m, -half_m), Vec2(half_m, -half_m), Vec2(half_m, half_m),
                 Vec2(-half_m, half_m)};
  wall.closed = true;
  map.walls.push_back(wall);
  map.start = Pose2{0.0, 0.0, 0.0};
  return map;
}

inline RobotProfile thesisRobot() {
  RobotProfileResult result =
      loadRobotProfileFile(std::string(IRGS_SOURCE_DIR) + "/resources/robots/thesis_robot.json");
  if (!result.profile)
    throw std::runtime_error("bundled thesis_robot.json does not load");
  return *result.profile;
}

inline RobotFactory simulatedFactory(std::uint64_t seed = 7) {
  return [seed](const WorldMap& map, const RobotProfile& profile) -> std::unique_ptr<Robot> {
    SimConfig config;
    config.seed = seed;
    return std::make_unique<SimulatedRobot>(map, profile, config);
  };
}

}  // namespace irgs::gui::test
