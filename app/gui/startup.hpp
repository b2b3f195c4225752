#pragma once
// Loading what irgs needs before it opens a window (robot profile, map), with every problem
// turned into lines for stderr, so a bad file ends the program with a clear message instead of
// an empty window.

#include <QString>
#include <QStringList>
#include <optional>

#include "core/robot/robot_profile.hpp"
#include "core/world/world_map.hpp"

namespace irgs::gui {

template <typename T>
struct Loaded {
  std::optional<T> value;  // empty on error
  QString file;            // absolute path of what was read
  QStringList errors;      // one diagnostic per line (file:line:col: error: field: message)
  QStringList warnings;
};

// `path` empty: the bundled resources/robots/thesis_robot.json.
Loaded<RobotProfile> loadStartupRobot(const QString& path);
// `path` empty: the bundled resources/maps/default.json.
Loaded<WorldMap> loadStartupMap(const QString& path);

}  // namespace irgs::gui
