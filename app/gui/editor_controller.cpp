#include "app/gui/editor_controller.hpp"

#include <QDateTime>
#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QGuiApplication>
#include <QMessageBox>
#include <QStandardPaths>
#include <QTabWidget>
#include <QUndoStack>
#include <cmath>
#include <exception>
#include <stdexcept>

#include "app/gui/map_file_actions.hpp"
#include "app/gui/session_controller.hpp"
#include "core/io/atomic_file.hpp"
#include "core/world/map_file.hpp"
#include "widgets/canvas/map_canvas.hpp"
#include "widgets/editor/editor_layer.hpp"
#include "widgets/editor/editor_model.hpp"
#include "widgets/editor/editor_panel.hpp"

namespace irgs::gui {
namespace {

std::filesystem::path toPath(const QString& path) {
  return std::filesystem::path(QFile::encodeName(path).toStdString());
}

QString defaultRecoveryDir() {
  const QString env = qEnvironmentVariable("IRGS_RECOVERY_DIR");
  if (!env.isEmpty())
    return env;
  QString base = QStandardPaths::writableLocation(QStandardPaths::AppLocalDataLocation);
  if (base.isEmpty())
    base = QDir::temp().filePath(QStringLiteral("irgs"));
  return QDir(base).filePath(QStringLiteral("recovery"));
}

}  // namespace

EditorController::EditorController(SessionController& session, MapFileActions& files,
                                   widgets::MapCanvas& canvas, QTabWidget& tabs,
                                   QWidget& dialog_parent)
    : QObject(&dialog_parent),
      session_(session),
      files_(files),
      canvas_(canvas),
      tabs_(tabs),
      dialog_parent_(dialog_parent) {
  model_ = new widgets::EditorModel(this);
  editing::ValidationSettings validation;  // the start pose needs room for this robot
  validation.robot_radius_m = session_.profile().bodyRadius();
  if (std::isfinite(validation.robot_radius_m) && validation.robot_radius_m > 0.0)
    model_->setValidationSettings(validation);
  model_->setMap(session_.worldMap());
  layer_ = new widgets::EditorLayer(canvas_, *model_);
  layer_->hide();
  panel_ = new widgets::EditorPanel(*model_, *layer_, &tabs_);
  tabs_.addTab(panel_, tr("Edit"));
  recovery_file_ = QDir(defaultRecoveryDir()).filePath(QString::fromLatin1(kRecoveryFileName));

  // Environment settings for scripted runs; bad values are reported and ignored.
  const QString period = qEnvironmentVariable("IRGS_AUTOSAVE_S");
  if (!period.isEmpty()) {
    bool ok = false;
    const double s = period.toDouble(&ok);
    if (ok && std::isfinite(s) && s > 0.0)
      autosave_s_ = s;
    else
      session_.report(EventLevel::kWarning,
                      tr("IRGS_AUTOSAVE_S=%1 is not a positive number of seconds; autosaving "
                         "every %2 s")
                          .arg(period)
                          .arg(autosave_s_));
  }
  const QString policy = qEnvironmentVariable("IRGS_RECOVERY").toLower();
  if (policy == QLatin1String("accept"))
    recovery_policy_ = RecoveryPolicy::kAccept;
  else if (policy == QLatin1String("discard"))
    recovery_policy_ = RecoveryPolicy::kDiscard;
  else if (!policy.isEmpty() && policy != QLatin1String("ask"))
    session_.report(EventLevel::kWarning,
                    tr("IRGS_RECOVERY=%1 is not ask, accept or discard; asking").arg(policy));

  connect(&tabs_, &QTabWidget::currentChanged, this,
          [this](int index) { setActive(tabs_.widget(index) == panel_); });
  connect(model_, &widgets::EditorModel::mapChanged, this, &EditorController::onModelChanged);
  connect(&model_->undoStack(), &QUndoStack::cleanChanged, this, [this](bool clean) {
    if (clean)
      removeRecoveryFile();  // back at the saved state: nothing to recover
    updateTabTitle();
    emit modifiedChanged(!clean);
  });
  connect(model_, &widgets::EditorModel::rejected, this, [this](const QString& reason) {
    session_.report(EventLevel::kWarning, tr("Edit refused: %1").arg(reason));
  });
  connect(layer_, &widgets::EditorLayer::message, this,
          [this](const QString& text) { session_.report(EventLevel::kInfo, text); });
  connect(panel_, &widgets::EditorPanel::issueActivated, this, [this](double x_m, double y_m) {
    canvas_.setView(Vec2(x_m, y_m), canvas_.pixelsPerMetre());
  });
  connect(&session_, &SessionController::worldLoaded, this, &EditorController::onWorldLoaded);
  connect(&files_, &MapFileActions::saved, this, [this] {
    model_->markSaved();
    removeRecoveryFile();
  });
  files_.setDiscardGuard([this] { return confirmDiscard(); });

  autosave_timer_.setInterval(static_cast<int>(std::lround(autosave_s_ * 1000.0)));
  connect(&autosave_timer_, &QTimer::timeout, this, &EditorController::autosaveNow);
  autosave_timer_.start();
}

EditorController::~EditorController() {
  files_.setDiscardGuard({});
}

void EditorController::setActive(bool active) {
  if (active != (tabs_.currentWidget() == panel_))
    tabs_.setCurrentWidget(active ? static_cast<QWidget*>(panel_) : tabs_.widget(0));
  if (active == active_)
    return;
  active_ = active;
  if (active) {
    layer_->setGeometry(canvas_.rect());
    layer_->show();
    layer_->raise();
    layer_->setFocus(Qt::OtherFocusReason);
  } else {
    layer_->cancelDraft();
    layer_->hide();
  }
}

bool EditorController::isModified() const {
  return model_->isModified();
}

void EditorController::setAutosaveInterval(double seconds) {
  if (!(seconds > 0.0) || !std::isfinite(seconds))
    throw std::invalid_argument("autosave interval must be a positive number of seconds");
  autosave_s_ = seconds;
  autosave_timer_.setInterval(static_cast<int>(std::lround(seconds * 1000.0)));
}

void EditorController::onModelChanged() {
  ++generation_;
  canvas_.setWorldMap(model_->map());
  if (pushing_)
    return;  // a new document from the session: it already has this map
  // The simulator runs on the edited map; the robot keeps its pose.
  pushing_ = true;
  try {
    session_.updateWorld(model_->map());
  } catch (const std::exception& e) {
    session_.report(
        EventLevel::kError,
        tr("The simulator cannot use the edited map: %1").arg(QString::fromUtf8(e.what())));
  }
  pushing_ = false;
}

void EditorController::onWorldLoaded() {
  if (pushing_)
    return;
  // Another map was opened: a new document (the old edits were saved or discarded first).
  pushing_ = true;
  model_->setMap(session_.worldMap());
  pushing_ = false;
  autosaved_generation_ = generation_;
  updateTabTitle();
}

bool EditorController::autosaveNow() {
  if (!model_->isModified() || autosaved_generation_ == generation_)
    return false;
  WorldMap map = model_->map();
  // The layers' files by absolute path: a `source` as written (relative to the map, or only a
  // file name until the map is saved) would not be found from the recovery file.
  if (map.raster && !map.raster->resolved_path.empty())
    map.raster->source = map.raster->resolved_path;
  if (map.floor_plan && !map.floor_plan->resolved_path.empty())
    map.floor_plan->source = map.floor_plan->resolved_path;
  map.extra[kRecoveryKey] = {
      {"source", files_.currentFile().toStdString()},
      {"saved_utc", QDateTime::currentDateTimeUtc().toString(Qt::ISODate).toStdString()}};
  std::optional<std::string> error;
  try {
    QDir().mkpath(QFileInfo(recovery_file_).absolutePath());
    error = writeFileAtomically(toPath(recovery_file_), serializeMap(map));
  } catch (const std::exception& e) {  // a non-finite number cannot be written
    error = e.what();
  }
  if (error) {
    session_.report(EventLevel::kWarning,
                    tr("Autosave failed: %1").arg(QString::fromStdString(*error)));
    return false;
  }
  autosaved_generation_ = generation_;
  emit autosaved(recovery_file_);
  return true;
}

bool EditorController::offerRecovery() {
  if (!QFileInfo::exists(recovery_file_))
    return false;
  const ReadFileResult read = readFile(toPath(recovery_file_));
  if (!read.ok()) {
    session_.report(
        EventLevel::kWarning,
        tr("Cannot read the recovery file: %1").arg(QString::fromStdString(read.error)));
    return false;
  }
  // Parse twice: first for the metadata (the source file gives the folder a raster is relative
  // to), then for real.
  MapLoadResult loaded = parseMapJson(read.bytes, recovery_file_.toStdString(),
                                      toPath(QFileInfo(recovery_file_).absolutePath()));
  QString source;
  if (loaded.map && loaded.map->extra.contains(kRecoveryKey)) {
    const nlohmann::json& meta = loaded.map->extra[kRecoveryKey];
    if (meta.is_object() && meta.contains("source") && meta["source"].is_string())
      source = QString::fromStdString(meta["source"].get<std::string>());
    if (!source.isEmpty())
      loaded = parseMapJson(read.bytes, recovery_file_.toStdString(),
                            toPath(QFileInfo(source).absolutePath()));
  }
  if (!loaded.map) {
    const QString bad = recovery_file_ + QStringLiteral(".unreadable");
    QFile::remove(bad);
    QFile::rename(recovery_file_, bad);
    session_.report(EventLevel::kError,
                    tr("The recovery file is damaged and was set aside as %1").arg(bad));
    for (const QString& line : MapFileActions::formatDiagnostics(loaded.diagnostics))
      session_.report(EventLevel::kError, line);
    return false;
  }
  WorldMap recovered = std::move(*loaded.map);
  std::string saved_utc;
  if (recovered.extra.contains(kRecoveryKey)) {
    const nlohmann::json& meta = recovered.extra[kRecoveryKey];
    if (meta.is_object() && meta.contains("saved_utc") && meta["saved_utc"].is_string())
      saved_utc = meta["saved_utc"].get<std::string>();
    recovered.extra.erase(std::string(kRecoveryKey));
  }

  RecoveryPolicy policy = recovery_policy_;
  if (policy == RecoveryPolicy::kAsk &&
      QGuiApplication::platformName() == QLatin1String("offscreen")) {
    session_.report(EventLevel::kWarning,
                    tr("Unsaved map edits were recovered in %1; start with IRGS_RECOVERY=accept "
                       "to restore them")
                        .arg(recovery_file_));
    return false;
  }
  if (policy == RecoveryPolicy::kAsk) {
    const QString what = source.isEmpty() ? tr("an unsaved map") : QFileInfo(source).fileName();
    const auto answer = QMessageBox::question(
        &dialog_parent_, tr("Recover map edits"),
        tr("IRGS did not shut down cleanly. Unsaved edits of %1 (autosaved %2) can be "
           "restored.\n\nRestore them?")
            .arg(what, QString::fromStdString(saved_utc)),
        QMessageBox::Yes | QMessageBox::No, QMessageBox::Yes);
    policy = answer == QMessageBox::Yes ? RecoveryPolicy::kAccept : RecoveryPolicy::kDiscard;
  }
  if (policy == RecoveryPolicy::kDiscard) {
    removeRecoveryFile();
    session_.report(EventLevel::kInfo, tr("Recovered map edits discarded"));
    return false;
  }

  // Edits belong on top of the file they were made to.
  if (!source.isEmpty() && QFileInfo::exists(source) &&
      QFileInfo(source).absoluteFilePath() != files_.currentFile()) {
    files_.openMap(source);
  }
  const bool restored = model_->tryApply([&](const WorldMap& m) {
    return editing::replaceContents(m, recovered, "Recover unsaved edits");
  });
  if (restored) {
    session_.report(EventLevel::kInfo,
                    tr("Restored unsaved map edits from %1").arg(recovery_file_));
    setActive(true);
    autosaveNow();  // the restored state is the new recovery point
  }
  return restored;
}

bool EditorController::confirmDiscard() {
  if (!model_->isModified())
    return true;
  UnsavedPolicy answer = unsaved_policy_;
  if (answer == UnsavedPolicy::kAsk) {
    const auto button = QMessageBox::warning(
        &dialog_parent_, tr("Unsaved map edits"), tr("The map has unsaved edits. Save them first?"),
        QMessageBox::Save | QMessageBox::Discard | QMessageBox::Cancel, QMessageBox::Save);
    answer = button == QMessageBox::Save      ? UnsavedPolicy::kSave
             : button == QMessageBox::Discard ? UnsavedPolicy::kDiscard
                                              : UnsavedPolicy::kCancel;
  }
  switch (answer) {
    case UnsavedPolicy::kSave:
      return files_.save();
    case UnsavedPolicy::kDiscard:
      removeRecoveryFile();
      return true;
    case UnsavedPolicy::kCancel:
    case UnsavedPolicy::kAsk:
      break;
  }
  return false;
}

void EditorController::shutdown() {
  autosave_timer_.stop();
  removeRecoveryFile();
}

void EditorController::removeRecoveryFile() {
  if (QFileInfo::exists(recovery_file_))
    QFile::remove(recovery_file_);
  autosaved_generation_ = generation_;
}

void EditorController::updateTabTitle() {
  const int index = tabs_.indexOf(panel_);
  if (index >= 0)
    tabs_.setTabText(index, model_->isModified() ? tr("Edit •") : tr("Edit"));
}

}  // namespace irgs::gui
