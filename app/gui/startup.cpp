#include "app/gui/startup.hpp"

#include <QFile>
#include <QFileInfo>
#include <filesystem>

#include "app/gui/resource_locator.hpp"
#include "core/robot/robot_profile_file.hpp"
#include "core/world/map_file.hpp"

namespace irgs::gui {
namespace {

std::filesystem::path toPath(const QString& path) {
  return std::filesystem::path(QFile::encodeName(path).toStdString());
}

// Resolves `path`, or the bundled resource when empty. Returns an empty string (and an error
// line) when the bundled resource cannot be found.
QString resolve(const QString& path, const QString& bundled, QStringList& errors) {
  if (!path.isEmpty())
    return QFileInfo(path).absoluteFilePath();
  const QString found = findResource(bundled);
  if (found.isEmpty())
    errors << QStringLiteral("bundled resource %1 not found in: %2")
                  .arg(bundled, resourceDirectories().join(QStringLiteral(", ")));
  return found;
}

template <typename T, typename Result>
void splitDiagnostics(const Result& result, Loaded<T>& out) {
  for (const Diagnostic& d : result.diagnostics) {
    (d.severity == Severity::kError ? out.errors : out.warnings)
        << QString::fromStdString(d.toString());
  }
}

}  // namespace

Loaded<RobotProfile> loadStartupRobot(const QString& path) {
  Loaded<RobotProfile> out;
  out.file = resolve(path, QStringLiteral("robots/thesis_robot.json"), out.errors);
  if (out.file.isEmpty())
    return out;
  RobotProfileResult result = loadRobotProfileFile(toPath(out.file));
  splitDiagnostics(result, out);
  if (result.profile && out.errors.isEmpty())
    out.value = std::move(*result.profile);
  else if (out.errors.isEmpty())
    out.errors << out.file + QStringLiteral(": error: the robot profile could not be read");
  return out;
}

Loaded<WorldMap> loadStartupMap(const QString& path) {
  Loaded<WorldMap> out;
  out.file = resolve(path, QStringLiteral("maps/default.json"), out.errors);
  if (out.file.isEmpty())
    return out;
  MapLoadResult result = loadAnyMap(toPath(out.file));
  splitDiagnostics(result, out);
  if (result.map && out.errors.isEmpty())
    out.value = std::move(*result.map);
  else if (out.errors.isEmpty())
    out.errors << out.file + QStringLiteral(": error: the map could not be read");
  return out;
}

}  // namespace irgs::gui
