#pragma once
// Finds the bundled resources (maps, robot profiles): in the source tree the build came from, or
// in an install next to the executable (<prefix>/bin/irgs -> <prefix>/share/irgs/resources).

#include <QString>
#include <QStringList>

namespace irgs::gui {

// Candidate resource directories, most specific first: $IRGS_RESOURCE_DIR, the install location
// relative to the executable, the source tree given at compile time.
QStringList resourceDirectories();

// Absolute path of `relative` (e.g. "maps/default.json") in the first directory holding it, or
// an empty string when no directory does.
QString findResource(const QString& relative);

}  // namespace irgs::gui
