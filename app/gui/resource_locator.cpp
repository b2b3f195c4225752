#include "app/gui/resource_locator.hpp"

#include <QCoreApplication>
#include <QDir>
#include <QFileInfo>

namespace irgs::gui {

QStringList resourceDirectories() {
  QStringList dirs;
  const QString env = qEnvironmentVariable("IRGS_RESOURCE_DIR");
  if (!env.isEmpty())
    dirs << env;
  if (QCoreApplication::instance() != nullptr)
    dirs << QDir(QCoreApplication::applicationDirPath())
                .absoluteFilePath(QStringLiteral("../share/irgs/resources"));
#ifdef IRGS_RESOURCE_DIR
  dirs << QStringLiteral(IRGS_RESOURCE_DIR);
#endif
  return dirs;
}

QString findResource(const QString& relative) {
  for (const QString& dir : resourceDirectories()) {
    const QFileInfo candidate(QDir(dir).filePath(relative));
    if (candidate.isFile())
      return candidate.absoluteFilePath();
  }
  return {};
}

}  // namespace irgs::gui
