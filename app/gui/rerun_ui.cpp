#include "app/gui/rerun_ui.hpp"

#include <QAction>
#include <QDialog>
#include <QFileDialog>
#include <QFileInfo>
#include <QHBoxLayout>
#include <QLabel>
#include <QMainWindow>
#include <QMenu>
#include <QMenuBar>
#include <QProgressDialog>
#include <QPushButton>
#include <QThread>
#include <QVBoxLayout>
#include <atomic>
#include <chrono>
#include <cmath>
#include <filesystem>

#include "app/gui/recording_ui.hpp"
#include "app/gui/rerun_dialog.hpp"
#include "app/gui/resource_locator.hpp"
#include "app/gui/session_controller.hpp"
#include "app/recording/recording_reader.hpp"
#include "app/recording/rerun_inputs.hpp"
#include "app/recording/rerun_output.hpp"
#include "widgets/replay/rerun_compare_view.hpp"

namespace irgs::gui {

namespace {

QString number(double v, int decimals = 4) {
  return QString::number(v, 'f', decimals);
}

QString count(std::size_t n) {
  return QString::number(static_cast<qulonglong>(n));
}

QString truthCell(const std::optional<TrajectoryDifference>& error) {
  if (!error)
    return QObject::tr("no truth");
  return QObject::tr("%1 / %2 / %3")
      .arg(number(error->rms_position_m), number(error->max_position_m),
           number(error->final_position_m));
}

}  // namespace

QStringList rerunMetricColumns() {
  return {QObject::tr("Metric"), QObject::tr("Recorded"), QObject::tr("Re-run"),
          QObject::tr("Comparison")};
}

std::vector<QStringList> rerunMetricRows(const recording::RerunResult& r) {
  const GridComparison& g = r.metrics.grid;
  const TrajectoryDifference& pose = r.metrics.pose;
  QStringList changed;
  for (const std::string& name :
       recording::changedRerunParameters(r.recorded.parameters, r.rerun.parameters))
    changed << QStringLiteral("%1 %2 → %3")
                   .arg(QString::fromStdString(name),
                        QString::fromStdString(
                            recording::rerunParameterValue(r.recorded.parameters, name)),
                        QString::fromStdString(
                            recording::rerunParameterValue(r.rerun.parameters, name)));
  auto grid_res = [](const recording::RerunRun& run) {
    return QObject::tr("%1 m").arg(run.grid.resolution_m());
  };
  return {
      {QObject::tr("Changed parameters"), QString(), QString(),
       changed.isEmpty() ? QObject::tr("none") : changed.join(QStringLiteral(", "))},
      {QObject::tr("Samples"), count(r.recorded.trajectory.size()),
       count(r.rerun.trajectory.size()), QString()},
      {QObject::tr("Grid resolution"), grid_res(r.recorded), grid_res(r.rerun),
       QObject::tr("compared on %1 m cells").arg(g.resolution_m)},
      {QObject::tr("Sonar readings integrated"), QString::number(r.recorded.mapping.integrated),
       QString::number(r.rerun.mapping.integrated), QString()},
      {QObject::tr("Explored area (m²)"), number(r.recorded.grid.exploredArea_m2(), 3),
       number(r.rerun.grid.exploredArea_m2(), 3), QString()},
      {QObject::tr("Occupied cells"), count(g.reference_occupied), count(g.candidate_occupied),
       QString()},
      {QObject::tr("Cell agreement"), QString(), QString(),
       QObject::tr("%1 (%2 of %3 cells)%4")
           .arg(number(g.agreement))
           .arg(g.same_class_cells)
           .arg(g.compared_cells)
           .arg(g.identical ? QObject::tr(", identical") : QString())},
      {QObject::tr("Occupied F1 (exact cells)"), QString(), QString(),
       QObject::tr("%1 (precision %2, recall %3)")
           .arg(number(g.occupied.f1), number(g.occupied.precision), number(g.occupied.recall))},
      {QObject::tr("Occupied F1 (within %1 cells)").arg(GridCompareOptions{}.tolerance_cells),
       QString(), QString(), number(g.occupied_tolerant.f1)},
      {QObject::tr("Pose difference RMS / max (m)"), QString(), QString(),
       QObject::tr("%1 / %2").arg(number(pose.rms_position_m), number(pose.max_position_m))},
      {QObject::tr("Heading difference RMS / max (°)"), QString(), QString(),
       QObject::tr("%1 / %2").arg(number(radToDeg(pose.rms_heading_rad), 3),
                                  number(radToDeg(pose.max_heading_rad), 3))},
      {QObject::tr("Error vs truth RMS / max / final (m)"), truthCell(r.recorded.truth_error),
       truthCell(r.rerun.truth_error), QString()},
  };
}

struct RerunUi::Job {
  recording::Recording recording;
  RobotProfile profile;
  WorldMap map;
  recording::RerunParameters recorded;
  recording::RerunParameters changed;
  std::atomic<double> progress{0.0};
  std::atomic<bool> cancel{false};
  recording::RerunResult result;
  double elapsed_s = 0.0;
};

RerunUi::RerunUi(SessionController& session, QMainWindow& window, QAction* after)
    : QObject(&window), session_(session), window_(window) {
  action_ = new QAction(tr("Re-run with &Parameters..."), this);
  action_->setToolTip(
      tr("Feed a recording's sensor stream into the mapper and estimator with changed "
         "parameters and compare with the recorded run"));
  connect(action_, &QAction::triggered, this, &RerunUi::choose);
  for (QAction* top : window_.menuBar()->actions()) {
    QMenu* menu = top->menu();
    if (menu == nullptr || menu->title() != QObject::tr("&File"))
      continue;
    const QList<QAction*> actions = menu->actions();
    QAction* before = nullptr;
    const qsizetype at = after != nullptr ? actions.indexOf(after) : -1;
    if (at >= 0 && at + 1 < actions.size()) {
      before = actions[at + 1];
    } else {
      for (QAction* action : actions) {
        if (action->isSeparator())
          before = action;  // before Quit
      }
    }
    menu->insertAction(before, action_);
    break;
  }
  poll_.setInterval(kProgressPoll_ms);
  connect(&poll_, &QTimer::timeout, this, [this] {
    if (progress_ && job_)
      progress_->setValue(static_cast<int>(std::lround(job_->progress.load() * 1000.0)));
  });
}

RerunUi::~RerunUi() {
  // Nothing here signals the session or the window: both may be half gone (see RecordingUi).
  poll_.stop();
  if (thread_ != nullptr) {
    job_->cancel = true;
    thread_->wait();
    delete thread_;
    thread_ = nullptr;
  }
  delete window_view_.data();  // it draws result_'s grids
}

void RerunUi::choose() {
  QString path;
  if (chooser_) {
    path = chooser_();
  } else {
    path = QFileDialog::getOpenFileName(&window_, tr("Re-run Recording"),
                                        RecordingUi::defaultRecordingsDir(QString()),
                                        tr("IRGS recordings (*%1);;All files (*)")
                                            .arg(QString::fromLatin1(recording::kFileSuffix)));
  }
  if (path.isEmpty())
    return;
  const QString problem = start(path);
  if (!problem.isEmpty())
    session_.report(EventLevel::kError, tr("Cannot re-run %1: %2").arg(path, problem));
}

QString RerunUi::start(const QString& path, std::optional<recording::RerunParameters> changed) {
  if (running())
    return tr("a re-run is already running");
  recording::LoadResult loaded = recording::loadRecording(path.toStdString());
  if (!loaded.recording)
    return QString::fromStdString(loaded.error);
  if (loaded.recording->receivedFrameCount() == 0)
    return tr(
        "the recording holds no received link bytes (no robot link and no simulator sample "
        "in it, or made before simulator sessions were recorded as frames)");
  auto job = std::make_shared<Job>();
  std::vector<std::string> warnings = loaded.warnings;
  job->recorded = recording::recordedRerunParameters(loaded.recording->meta, &warnings);
  std::vector<std::filesystem::path> dirs;
  for (const QString& dir : resourceDirectories())
    dirs.emplace_back(dir.toStdString());
  recording::RerunInputs inputs =
      recording::resolveRerunInputs(*loaded.recording, {}, {}, dirs, session_.profile());
  warnings.insert(warnings.end(), inputs.warnings.begin(), inputs.warnings.end());
  for (const std::string& warning : warnings)
    session_.report(EventLevel::kWarning, QString::fromStdString(warning));
  if (!inputs.profile)
    return QString::fromStdString(inputs.error);

  const QString name = QFileInfo(path).fileName();
  if (!changed) {
    RerunDialog dialog(name, job->recorded, &window_);
    if (dialog_hook_)
      dialog_hook_(dialog);
    if (dialog.exec() != QDialog::Accepted)
      return {};
    changed = dialog.parameters();  // accept() checked them
    if (!changed)
      return dialog.error();
  }
  job->changed = *changed;
  job->recording = std::move(*loaded.recording);
  job->profile = *inputs.profile;
  job->map = std::move(inputs.map);
  job_ = job;
  result_name_ = name;

  thread_ = QThread::create([job] {
    const auto t0 = std::chrono::steady_clock::now();
    job->result = recording::rerunRecording(job->recording, job->profile, job->map, job->recorded,
                                            job->changed, [job](double f) {
                                              job->progress = f;
                                              return !job->cancel.load();
                                            });
    job->elapsed_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  });
  connect(thread_, &QThread::finished, this, &RerunUi::onWorkerDone);
  progress_ =
      new QProgressDialog(tr("Re-running %1...").arg(name), tr("Cancel"), 0, 1000, &window_);
  progress_->setObjectName(QStringLiteral("rerunProgress"));
  progress_->setWindowTitle(tr("Re-run"));
  progress_->setMinimumDuration(200);
  progress_->setAutoClose(false);
  progress_->setAutoReset(false);
  connect(progress_, &QProgressDialog::canceled, this, &RerunUi::cancel);
  poll_.start();
  session_.report(EventLevel::kInfo,
                  tr("Re-running %1 (%2 changed parameters)")
                      .arg(name)
                      .arg(recording::changedRerunParameters(job->recorded, job->changed).size()));
  thread_->start();
  return {};
}

void RerunUi::cancel() {
  if (job_)
    job_->cancel = true;
}

void RerunUi::onWorkerDone() {
  poll_.stop();
  if (thread_ != nullptr) {
    thread_->wait();
    thread_->deleteLater();
    thread_ = nullptr;
  }
  if (progress_) {
    progress_->disconnect(this);
    progress_->deleteLater();
  }
  std::shared_ptr<Job> job = std::move(job_);
  if (!job)
    return;
  if (!job->result.error.empty()) {
    const QString message = QString::fromStdString(job->result.error);
    session_.report(job->result.cancelled ? EventLevel::kInfo : EventLevel::kError,
                    tr("Re-run of %1: %2").arg(result_name_, message));
    emit finished(false, message);
    return;
  }
  delete window_view_.data();  // the old window draws the old result's grids
  view_ = nullptr;
  result_map_ = job->map;
  result_profile_ = job->profile;
  result_ = std::make_shared<const recording::RerunResult>(std::move(job->result));
  const GridComparison& g = result_->metrics.grid;
  const QString message =
      tr("Re-run of %1: %2 samples in %3 s; cell agreement %4, occupied F1 %5, pose "
         "difference RMS %6 m")
          .arg(result_name_)
          .arg(result_->samples)
          .arg(job->elapsed_s, 0, 'f', 2)
          .arg(g.agreement, 0, 'f', 4)
          .arg(g.occupied.f1, 0, 'f', 4)
          .arg(result_->metrics.pose.rms_position_m, 0, 'f', 4);
  session_.report(EventLevel::kInfo, message);
  showResult();
  emit finished(true, message);
}

void RerunUi::showResult() {
  auto* top = new QWidget(&window_, Qt::Window);
  top->setObjectName(QStringLiteral("rerunWindow"));
  top->setAttribute(Qt::WA_DeleteOnClose);
  top->setWindowTitle(tr("Re-run of %1: recorded vs re-run").arg(result_name_));
  auto* layout = new QVBoxLayout(top);
  view_ = new widgets::RerunCompareView(top);
  layout->addWidget(view_, 1);
  auto* buttons = new QHBoxLayout;
  auto* save = new QPushButton(tr("Save Outputs..."), top);
  save->setToolTip(
      tr("Write the maps (PNG, ROS map), trajectories (CSV) and metrics (JSON) as "
         "irgs-rerun does"));
  auto* close = new QPushButton(tr("Close"), top);
  buttons->addStretch(1);
  buttons->addWidget(save);
  buttons->addWidget(close);
  layout->addLayout(buttons);
  connect(close, &QPushButton::clicked, top, &QWidget::close);
  connect(save, &QPushButton::clicked, this, [this, top] {
    const QString dir = QFileDialog::getExistingDirectory(top, tr("Save Re-run Outputs"));
    if (dir.isEmpty())
      return;
    const QString problem = saveOutputs(dir);
    session_.report(problem.isEmpty() ? EventLevel::kInfo : EventLevel::kError,
                    problem.isEmpty() ? tr("Re-run outputs written to %1").arg(dir) : problem);
  });
  // A closed window must not leave a dangling view pointer.
  connect(top, &QObject::destroyed, this, [this] { view_ = nullptr; });

  view_->setWorldMap(result_map_);
  view_->setRobotProfile(result_profile_);
  auto poses = [](const recording::RerunRun& run) {
    std::vector<Pose2> out;
    out.reserve(run.trajectory.size());
    for (const recording::RerunPose& p : run.trajectory)
      out.push_back(p.pose);
    return out;
  };
  std::vector<Pose2> truth;
  for (const recording::RerunPose& p : result_->recorded.trajectory) {
    if (p.truth)
      truth.push_back(*p.truth);
  }
  auto title = [](const char* what, const recording::RerunRun& run) {
    const std::string estimator = recording::rerunParameterValue(run.parameters, "estimator");
    return tr("%1: grid %2 m, valid distance %3, estimator %4")
        .arg(tr(what))
        .arg(run.grid.resolution_m())
        .arg(run.parameters.validDistance() ? tr("%1 m").arg(*run.parameters.validDistance())
                                            : tr("max range"))
        .arg(QString::fromStdString(estimator));
  };
  view_->setRuns(
      {title("Recorded", result_->recorded), &result_->recorded.grid, poses(result_->recorded)},
      {title("Re-run", result_->rerun), &result_->rerun.grid, poses(result_->rerun)}, truth);
  view_->setMetrics(rerunMetricColumns(), rerunMetricRows(*result_));
  top->resize(1200, 800);
  window_view_ = top;
  top->show();
}

QString RerunUi::saveOutputs(const QString& dir) const {
  if (!result_)
    return tr("no re-run result to save");
  const std::string error =
      recording::writeRerunOutputs(*result_, dir.toStdString(), result_name_.toStdString());
  return QString::fromStdString(error);
}

}  // namespace irgs::gui
