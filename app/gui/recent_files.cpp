#include "app/gui/recent_files.hpp"

#include <QFileInfo>

namespace irgs::gui {

QStringList addRecentFile(const QStringList& recent, const QString& path, int max) {
  const QString absolute = QFileInfo(path).absoluteFilePath();
  QStringList out{absolute};
  for (const QString& entry : recent) {
    if (out.size() >= max)
      break;
    if (QFileInfo(entry).absoluteFilePath() != absolute)
      out << entry;
  }
  return out;
}

QStringList pruneRecentFiles(const QStringList& recent, int max) {
  QStringList out;
  for (const QString& entry : recent) {
    if (out.size() >= max)
      break;
    if (QFileInfo(entry).isFile() && !out.contains(entry))
      out << entry;
  }
  return out;
}

}  // namespace irgs::gui
