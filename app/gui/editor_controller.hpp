#pragma once
// The map editor as a mode of the main window (the "Edit" tab): an EditorModel on the session's
// map, the tool layer over the canvas while the tab is shown, the side panel in the tab.
//
// The simulator runs on what is being edited: every change goes to the session with
// SessionController::updateWorld (the robot keeps its pose). Saving goes through MapFileActions
// (which writes the session's map, i.e. the edited one); a save marks the edits saved.
// Unsaved edits are protected: opening another map or closing the window asks first, and a
// timer autosaves them every N seconds to a recovery file written atomically. At start a
// recovery file left behind by a crash is offered for restoring; the restore is one undoable
// step on top of the map that was being edited.
//
// Environment (for scripted and offscreen runs):
//   IRGS_AUTOSAVE_S    autosave period, seconds (default 30)
//   IRGS_RECOVERY      ask | accept | discard: what to do with a recovery file at start
//                      (default ask; on the offscreen platform "ask" only reports it)
//   IRGS_RECOVERY_DIR  folder of the recovery file (default: the app data folder + /recovery)

#include <QObject>
#include <QString>
#include <QTimer>
#include <cstdint>

class QTabWidget;
class QWidget;

namespace irgs::widgets {
class EditorLayer;
class EditorModel;
class EditorPanel;
class MapCanvas;
}  // namespace irgs::widgets

namespace irgs::gui {

class MapFileActions;
class SessionController;

class EditorController : public QObject {
  Q_OBJECT

 public:
  static constexpr double kDefaultAutosave_s = 30.0;
  static constexpr const char* kRecoveryFileName = "editor-recovery.json";
  static constexpr const char* kRecoveryKey = "x-irgs-recovery";  // metadata in the file

  enum class RecoveryPolicy { kAsk, kAccept, kDiscard };
  // What confirmDiscard() does with unsaved edits; kAsk shows a dialog.
  enum class UnsavedPolicy { kAsk, kSave, kDiscard, kCancel };

  // Adds the "Edit" tab to `tabs` and the tool layer to `canvas`. All references must outlive
  // the controller; `dialog_parent` parents its dialogs and owns it.
  EditorController(SessionController& session, MapFileActions& files, widgets::MapCanvas& canvas,
                   QTabWidget& tabs, QWidget& dialog_parent);
  ~EditorController() override;

  widgets::EditorModel& model() const { return *model_; }
  widgets::EditorLayer& layer() const { return *layer_; }
  widgets::EditorPanel& panel() const { return *panel_; }

  // Whether the Edit tab is shown (the tool layer is active); setActive switches the tab.
  bool isActive() const { return active_; }
  void setActive(bool active);

  bool isModified() const;
  const QString& recoveryFile() const { return recovery_file_; }
  void setRecoveryFile(const QString& path) { recovery_file_ = path; }
  double autosaveInterval_s() const { return autosave_s_; }
  void setAutosaveInterval(double seconds);  // > 0; throws std::invalid_argument otherwise
  void setRecoveryPolicy(RecoveryPolicy policy) { recovery_policy_ = policy; }
  void setUnsavedPolicy(UnsavedPolicy policy) { unsaved_policy_ = policy; }

  // Writes the unsaved edits to the recovery file (atomically) if they changed since the last
  // autosave. Returns whether the file was written.
  bool autosaveNow();
  // Offers the recovery file left by a crash, per the recovery policy. Returns whether edits
  // were restored.
  bool offerRecovery();
  // Before the edited map is replaced or the window closes: true when it may go ahead (nothing
  // unsaved, saved, or discarded), false to cancel.
  bool confirmDiscard();
  // A clean exit: stops autosaving and removes the recovery file.
  void shutdown();

 signals:
  void modifiedChanged(bool modified);
  void autosaved(const QString& path);

 private:
  void onModelChanged();
  void onWorldLoaded();
  void removeRecoveryFile();
  void updateTabTitle();

  SessionController& session_;
  MapFileActions& files_;
  widgets::MapCanvas& canvas_;
  QTabWidget& tabs_;
  QWidget& dialog_parent_;
  widgets::EditorModel* model_ = nullptr;
  widgets::EditorLayer* layer_ = nullptr;
  widgets::EditorPanel* panel_ = nullptr;
  bool active_ = false;
  bool pushing_ = false;  // the session's world is being replaced by us

  QTimer autosave_timer_;
  double autosave_s_ = kDefaultAutosave_s;
  std::uint64_t generation_ = 0;            // bumped by every change of the edited map
  std::uint64_t autosaved_generation_ = 0;  // what the recovery file holds
  QString recovery_file_;
  RecoveryPolicy recovery_policy_ = RecoveryPolicy::kAsk;
  UnsavedPolicy unsaved_policy_ = UnsavedPolicy::kAsk;
};

}  // namespace irgs::gui
