#include "app/gui/map_file_actions.hpp"

#include <QAction>
#include <QDir>
#include <QFile>
#include <QFileDialog>
#include <QFileInfo>
#include <QMenu>
#include <QMessageBox>
#include <QSettings>
#include <exception>

#include "app/gui/app_settings.hpp"
#include "app/gui/recent_files.hpp"
#include "app/gui/session_controller.hpp"
#include "core/world/map_file.hpp"

namespace irgs::gui {
namespace {

// Diagnostics shown in the dialog body; the full list is always in the details pane.
constexpr int kMaxDiagnosticsInBody = 12;
constexpr int kMaxDiagnosticsInConsole = 50;

std::filesystem::path toPath(const QString& path) {
  return std::filesystem::path(QFile::encodeName(path).toStdString());
}

bool isJsonMap(const QString& path) {
  return QFileInfo(path).suffix().compare(QStringLiteral("json"), Qt::CaseInsensitive) == 0;
}

}  // namespace

MapFileActions::MapFileActions(SessionController& session, QSettings& settings,
                               QWidget& dialog_parent)
    : QObject(&dialog_parent),
      session_(session),
      settings_(settings),
      dialog_parent_(dialog_parent) {
  open_ = new QAction(tr("&Open Map…"), this);
  open_->setShortcut(QKeySequence::Open);
  open_->setStatusTip(tr("Open an IRGS JSON map or a ROS map (YAML + PGM)"));
  connect(open_, &QAction::triggered, this, &MapFileActions::openWithDialog);

  save_ = new QAction(tr("&Save Map"), this);
  save_->setShortcut(QKeySequence::Save);
  save_->setStatusTip(tr("Save the current map as IRGS JSON"));
  connect(save_, &QAction::triggered, this, &MapFileActions::save);

  save_as_ = new QAction(tr("Save Map &As…"), this);
  save_as_->setShortcut(QKeySequence::SaveAs);
  connect(save_as_, &QAction::triggered, this, &MapFileActions::saveAs);

  recent_menu_ = new QMenu(tr("Open &Recent"), &dialog_parent_);
  settings_.setValue(QString::fromLatin1(settings_key::kRecentFiles), recentFiles());
  rebuildRecentMenu();
}

QStringList MapFileActions::recentFiles() const {
  return pruneRecentFiles(
      settings_.value(QString::fromLatin1(settings_key::kRecentFiles)).toStringList());
}

QStringList MapFileActions::formatDiagnostics(const std::vector<Diagnostic>& diagnostics) {
  QStringList lines;
  for (const Diagnostic& d : diagnostics)
    lines << QString::fromStdString(d.toString());
  return lines;
}

bool MapFileActions::openMap(const QString& path) {
  if (discard_guard_ && !discard_guard_())
    return false;
  MapLoadResult result = loadAnyMap(toPath(path));
  const QStringList lines = formatDiagnostics(result.diagnostics);
  if (!result.map || hasErrors(result.diagnostics)) {
    QMessageBox box(QMessageBox::Warning, tr("Cannot open map"),
                    tr("Could not open the map “%1”.").arg(QFileInfo(path).fileName()),
                    QMessageBox::Ok, &dialog_parent_);
    QStringList body = lines.mid(0, kMaxDiagnosticsInBody);
    if (lines.size() > kMaxDiagnosticsInBody)
      body << tr("… and %1 more (see Show Details).").arg(lines.size() - kMaxDiagnosticsInBody);
    if (body.isEmpty())
      body << tr("The file could not be read.");
    box.setInformativeText(body.join(QLatin1Char('\n')) + tr("\n\nThe current map is unchanged."));
    box.setDetailedText(lines.join(QLatin1Char('\n')));
    box.exec();
    // The console keeps the record after the dialog is closed.
    session_.report(
        EventLevel::kError,
        tr("Map %1 rejected; the current map is unchanged").arg(QFileInfo(path).fileName()));
    for (const QString& line : lines.mid(0, kMaxDiagnosticsInConsole))
      session_.report(EventLevel::kError, line);
    return false;
  }
  try {
    session_.loadWorld(std::move(*result.map), QFileInfo(path).absoluteFilePath());
  } catch (const std::exception& e) {  // e.g. a raster the simulator cannot use
    QMessageBox::warning(&dialog_parent_, tr("Cannot open map"),
                         tr("The map “%1” loaded but cannot be simulated:\n%2\n\nThe current map "
                            "is unchanged.")
                             .arg(QFileInfo(path).fileName(), QString::fromUtf8(e.what())));
    session_.report(EventLevel::kError,
                    tr("Map %1 cannot be simulated: %2")
                        .arg(QFileInfo(path).fileName(), QString::fromUtf8(e.what())));
    return false;
  }
  for (const QString& line : lines)
    session_.report(EventLevel::kWarning, line);
  setCurrentFile(path);
  return true;
}

void MapFileActions::setCurrentFile(const QString& path) {
  current_file_ = QFileInfo(path).absoluteFilePath();
  remember(current_file_);
  emit currentFileChanged(current_file_);
}

void MapFileActions::openWithDialog() {
  const QString path = QFileDialog::getOpenFileName(
      &dialog_parent_, tr("Open Map"), dialogDirectory(),
      tr("Maps (*.json *.yaml *.yml);;IRGS maps (*.json);;ROS maps (*.yaml *.yml);;All files (*)"));
  if (!path.isEmpty())
    openMap(path);
}

bool MapFileActions::save() {
  // A ROS map (or a map without a file) cannot be written back in place: save as JSON instead.
  if (current_file_.isEmpty() || !isJsonMap(current_file_))
    return saveAs();
  return saveTo(current_file_);
}

bool MapFileActions::saveAs() {
  QString suggestion = current_file_.isEmpty()
                           ? QDir(dialogDirectory()).filePath(QStringLiteral("map.json"))
                           : current_file_;
  if (!isJsonMap(suggestion)) {
    const QFileInfo info(suggestion);
    suggestion = info.dir().filePath(info.completeBaseName() + QStringLiteral(".json"));
  }
  QString path = QFileDialog::getSaveFileName(&dialog_parent_, tr("Save Map As"), suggestion,
                                              tr("IRGS maps (*.json)"));
  if (path.isEmpty())
    return false;
  if (QFileInfo(path).suffix().isEmpty())
    path += QStringLiteral(".json");
  if (!saveTo(path))
    return false;
  setCurrentFile(path);
  return true;
}

bool MapFileActions::saveTo(const QString& path) {
  std::optional<std::string> error;
  try {
    error = saveMapFile(session_.worldMap(), toPath(path));
  } catch (const std::invalid_argument& e) {  // a non-finite number cannot be written as JSON
    error = e.what();
  }
  if (error) {
    QMessageBox::warning(
        &dialog_parent_, tr("Cannot save map"),
        tr("Could not save the map to “%1”:\n%2").arg(path, QString::fromStdString(*error)));
    session_.report(EventLevel::kError,
                    tr("Saving %1 failed: %2").arg(path, QString::fromStdString(*error)));
    return false;
  }
  session_.report(EventLevel::kInfo, tr("Map saved to %1").arg(path));
  emit saved(QFileInfo(path).absoluteFilePath());
  return true;
}

void MapFileActions::remember(const QString& path) {
  settings_.setValue(QString::fromLatin1(settings_key::kRecentFiles),
                     addRecentFile(recentFiles(), path));
  settings_.setValue(QString::fromLatin1(settings_key::kLastMap), path);
  settings_.setValue(QString::fromLatin1(settings_key::kLastDirectory),
                     QFileInfo(path).absolutePath());
  rebuildRecentMenu();
}

QString MapFileActions::dialogDirectory() const {
  const QString dir = settings_.value(QString::fromLatin1(settings_key::kLastDirectory)).toString();
  return QFileInfo(dir).isDir() ? dir : QDir::homePath();
}

void MapFileActions::rebuildRecentMenu() {
  recent_menu_->clear();
  const QStringList recent = recentFiles();
  for (int i = 0; i < recent.size(); ++i) {
    const QString path = recent[i];
    // "&1 name.json — /full/dir" : the digit is the menu accelerator.
    QAction* action = recent_menu_->addAction(
        QStringLiteral("&%1  %2").arg(i + 1).arg(QFileInfo(path).fileName()));
    action->setStatusTip(path);
    action->setToolTip(path);
    connect(action, &QAction::triggered, this, [this, path] {
      if (!QFileInfo(path).isFile()) {
        QMessageBox::warning(
            &dialog_parent_, tr("Map not found"),
            tr("“%1” no longer exists; it was removed from the recent list.").arg(path));
        settings_.setValue(QString::fromLatin1(settings_key::kRecentFiles), recentFiles());
        rebuildRecentMenu();
        return;
      }
      openMap(path);
    });
  }
  if (!recent.isEmpty()) {
    recent_menu_->addSeparator();
    recent_menu_->addAction(tr("Clear List"), this, [this] {
      settings_.setValue(QString::fromLatin1(settings_key::kRecentFiles), QStringList{});
      rebuildRecentMenu();
    });
  }
  recent_menu_->setEnabled(!recent.isEmpty());
}

}  // namespace irgs::gui
