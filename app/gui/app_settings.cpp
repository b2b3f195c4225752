#include "app/gui/app_settings.hpp"

#include <QFile>

namespace irgs::gui {

std::unique_ptr<QSettings> openSettings(const QString& file) {
  QString path = file;
  if (path.isEmpty())
    path = qEnvironmentVariable("IRGS_SETTINGS_FILE");
  if (!path.isEmpty())
    return std::make_unique<QSettings>(path, QSettings::IniFormat);
  return std::make_unique<QSettings>(QString::fromLatin1(kOrganisation),
                                     QString::fromLatin1(kApplication));
}

bool restrictSettingsToOwner(QSettings& settings) {
  settings.sync();
  if (settings.status() != QSettings::NoError)
    return false;
  return QFile::setPermissions(settings.fileName(),
                               QFileDevice::ReadOwner | QFileDevice::WriteOwner);
}

}  // namespace irgs::gui
