#pragma once
// The File menu's map actions: open (with every diagnostic shown when a file is rejected, the
// current map left untouched), open recent (persisted, bounded, missing files dropped), save and
// save as (atomic JSON writes).

#include <QObject>
#include <QString>
#include <QStringList>
#include <functional>
#include <vector>

#include "core/io/diagnostic.hpp"

class QAction;
class QMenu;
class QSettings;
class QWidget;

namespace irgs::gui {

class SessionController;

class MapFileActions : public QObject {
  Q_OBJECT

 public:
  // `dialog_parent` parents the file and message dialogs; all three must outlive this object.
  MapFileActions(SessionController& session, QSettings& settings, QWidget& dialog_parent);

  QAction* openAction() const { return open_; }
  QAction* saveAction() const { return save_; }
  QAction* saveAsAction() const { return save_as_; }
  QMenu* recentMenu() const { return recent_menu_; }

  // Loads `path` into the session. On errors shows a dialog listing every diagnostic and keeps
  // the current map; warnings go to the console. Returns whether the map was loaded.
  bool openMap(const QString& path);
  // Records a map the session already holds (loaded at startup) as the current file.
  void setCurrentFile(const QString& path);
  const QString& currentFile() const { return current_file_; }
  QStringList recentFiles() const;

  // Asked before another map replaces the current one (open, open recent): returning false
  // cancels the open (the map editor asks about unsaved edits here). None by default.
  void setDiscardGuard(std::function<bool()> guard) { discard_guard_ = std::move(guard); }

  // "file:line:col: error: field: message" lines, one per diagnostic.
  static QStringList formatDiagnostics(const std::vector<Diagnostic>& diagnostics);

 signals:
  void currentFileChanged(const QString& path);
  void saved(const QString& path);  // the session's map was written to path

 public slots:
  void openWithDialog();
  bool save();
  bool saveAs();

 private:
  bool saveTo(const QString& path);
  void remember(const QString& path);
  void rebuildRecentMenu();
  QString dialogDirectory() const;

  SessionController& session_;
  QSettings& settings_;
  QWidget& dialog_parent_;
  QString current_file_;
  std::function<bool()> discard_guard_;
  QAction* open_ = nullptr;
  QAction* save_ = nullptr;
  QAction* save_as_ = nullptr;
  QMenu* recent_menu_ = nullptr;
};

}  // namespace irgs::gui
