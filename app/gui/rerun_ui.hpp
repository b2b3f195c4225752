#pragma once
// File > Re-run with Parameters... (issue 6 item 3; docs/gui.md "Re-run with parameters"): pick
// a recording, edit the parameters (RerunDialog, prefilled with the recording's), run the
// re-run engine (app/recording/rerun_engine.hpp) on a worker thread with a progress dialog that
// can cancel it, then open a window with the recorded and the re-run maps side by side, both
// trajectories and the metrics (widgets/replay/rerun_compare_view.hpp), and a button that
// writes the same files irgs-rerun writes.

#include <QObject>
#include <QPointer>
#include <QString>
#include <QStringList>
#include <QTimer>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "app/recording/rerun_engine.hpp"

class QAction;
class QMainWindow;
class QProgressDialog;
class QThread;
class QWidget;

namespace irgs::widgets {
class RerunCompareView;
}

namespace irgs::gui {

class SessionController;
class RerunDialog;

// The metrics table of a result: metric, recorded, re-run, comparison.
QStringList rerunMetricColumns();
std::vector<QStringList> rerunMetricRows(const recording::RerunResult& result);

class RerunUi : public QObject {
  Q_OBJECT

 public:
  static constexpr int kProgressPoll_ms = 50;

  // Adds the action to the window's File menu (after Open Recording... when `after` is given).
  RerunUi(SessionController& session, QMainWindow& window, QAction* after = nullptr);
  ~RerunUi() override;

  QAction* action() const { return action_; }

  // Hooks for tests: which file to re-run (default: a file dialog) and what to do with the
  // dialog before it is shown modally (default: nothing).
  using Chooser = std::function<QString()>;
  void setRecordingChooser(Chooser chooser) { chooser_ = std::move(chooser); }
  using DialogHook = std::function<void(RerunDialog&)>;
  void setDialogHook(DialogHook hook) { dialog_hook_ = std::move(hook); }

  // Loads `path`, asks for the parameters (`changed` skips the dialog) and starts the worker.
  // Empty when started (or the dialog was cancelled), else why not.
  QString start(const QString& path,
                std::optional<recording::RerunParameters> changed = std::nullopt);
  bool running() const { return thread_ != nullptr; }
  void cancel();

  // The last finished run and its window (null before the first, or after a failure).
  const recording::RerunResult* result() const { return result_.get(); }
  QWidget* compareWindow() const { return window_view_; }
  widgets::RerunCompareView* compareView() const { return view_; }
  // Writes the irgs-rerun files of the last result into `dir`; empty on success.
  QString saveOutputs(const QString& dir) const;

 signals:
  void finished(bool ok, const QString& message);

 private:
  struct Job;
  void choose();
  void onWorkerDone();
  void showResult();

  SessionController& session_;
  QMainWindow& window_;
  QAction* action_ = nullptr;
  Chooser chooser_;
  DialogHook dialog_hook_;

  std::shared_ptr<Job> job_;
  QThread* thread_ = nullptr;
  QPointer<QProgressDialog> progress_;
  QTimer poll_;

  std::shared_ptr<const recording::RerunResult> result_;
  QString result_name_;
  WorldMap result_map_;
  RobotProfile result_profile_;
  QPointer<QWidget> window_view_;
  widgets::RerunCompareView* view_ = nullptr;
};

}  // namespace irgs::gui
