#include "app/gui/recording_ui.hpp"

#include <QAction>
#include <QDateTime>
#include <QDir>
#include <QDockWidget>
#include <QFileDialog>
#include <QFileInfo>
#include <QMainWindow>
#include <QMenu>
#include <QMenuBar>
#include <QScopedValueRollback>
#include <QStandardPaths>
#include <cmath>
#include <exception>
#include <mutex>
#include <stdexcept>

#include "app/gui/link_controller.hpp"
#include "app/recording/recording_reader.hpp"
#include "app/recording/replay_player.hpp"
#include "app/recording/rerun_parameters.hpp"
#include "app/recording/session_recorder.hpp"
#include "comms/robot/remote_robot.hpp"
#include "comms/transport/io_thread.hpp"
#include "comms/transport/replay_transport.hpp"
#include "widgets/link/link_health_panel.hpp"
#include "widgets/replay/replay_bar.hpp"

namespace irgs::gui {

namespace {

constexpr int kRecorderCheck_ms = 1000;
constexpr int kDrainPoll_ms = 50;
// Polls with nothing new before a finished replay counts as drained: 0.3 s, three times the
// telemetry assembler's hold time, so its last sample has been released and integrated.
constexpr int kDrainStablePolls = 6;

const char* levelName(EventLevel level) {
  switch (level) {
    case EventLevel::kWarning:
      return "warning";
    case EventLevel::kError:
      return "error";
    case EventLevel::kSensor:
      return "sensor";
    case EventLevel::kInfo:
      break;
  }
  return "info";
}

std::vector<widgets::ReplayMark> timelineMarks(const recording::Recording& recording) {
  std::vector<widgets::ReplayMark> marks;
  for (const recording::RecordedEvent& event : recording.events) {
    widgets::ReplayMark mark;
    mark.t_s = event.t_s;
    mark.text = QString::fromStdString(event.text);
    if (event.kind == "error") {
      mark.kind = widgets::ReplayMarkKind::kError;
    } else if (event.kind == "warning" || event.kind == "link") {
      mark.kind = widgets::ReplayMarkKind::kWarning;
    } else if (event.kind == "info" &&
               (mark.text.startsWith(QStringLiteral("Mode:")) ||
                mark.text.contains(QStringLiteral("link"), Qt::CaseInsensitive) ||
                mark.text.startsWith(QStringLiteral("Map building")) ||
                mark.text.startsWith(QStringLiteral("Behaviour")))) {
      mark.kind = widgets::ReplayMarkKind::kInfo;  // mode changes, link state, phases
    } else {
      continue;
    }
    marks.push_back(std::move(mark));
  }
  return marks;
}

}  // namespace

// The recorder behind LinkController's tap; swapped when recording starts or stops, while links
// built earlier keep the same forwarding tap.
struct RecordingUi::TapTarget {
  std::mutex mutex;
  comms::FrameTap tap;
};

RecordingUi::RecordingUi(SessionController& session, LinkController& link, QMainWindow& window)
    : QObject(&window),
      session_(session),
      link_(link),
      window_(window),
      tap_target_(std::make_shared<TapTarget>()) {
  open_action_ = new QAction(tr("Open &Recording..."), this);
  open_action_->setToolTip(tr("Replay a recorded session as the robot link"));
  connect(open_action_, &QAction::triggered, this, &RecordingUi::chooseAndOpenReplay);
  // The window's File menu: insert before Quit (the last separator), keeping MainWindow's own
  // layout of the menu untouched.
  for (QAction* top : window_.menuBar()->actions()) {
    QMenu* menu = top->menu();
    if (menu == nullptr || menu->title() != QObject::tr("&File"))
      continue;
    QAction* before = nullptr;
    for (QAction* action : menu->actions()) {
      if (action->isSeparator())
        before = action;
    }
    menu->insertAction(before, open_action_);
    break;
  }

  bar_ = new widgets::ReplayBar;
  dock_ = new QDockWidget(tr("Replay"), &window_);
  dock_->setObjectName(QStringLiteral("replayDock"));
  dock_->setWidget(bar_);
  dock_->setFeatures(QDockWidget::NoDockWidgetFeatures);
  window_.addDockWidget(Qt::BottomDockWidgetArea, dock_);
  dock_->hide();
  connect(bar_, &widgets::ReplayBar::closeRequested, this, &RecordingUi::closeReplay);

  link_.setFrameTap([target = tap_target_](comms::TapDirection direction,
                                           std::chrono::steady_clock::time_point time,
                                           std::span<const std::uint8_t> bytes) {
    const std::lock_guard lock(target->mutex);
    if (target->tap)
      target->tap(direction, time, bytes);
  });
  connect(&session_, &SessionController::robotStateChanged, this, &RecordingUi::onRobotState);
  connect(&session_, &SessionController::sampleIntegrated, this, &RecordingUi::onSampleIntegrated);
  connect(&session_, &SessionController::robotReplaced, this, [this] {
    simulator_frames_.reset();  // a new robot: its stream starts over with a heartbeat
    trajectory_.clear();
    expect_initial_sample_ = true;
    if (replaying() && !installing_)
      onRobotReplacedElsewhere();
  });
  connect(&session_, &SessionController::ticked, this, &RecordingUi::onTicked);
  connect(&session_, &SessionController::consoleEvent, this,
          [this](EventLevel level, double, const QString& text) { onConsole(level, text); });
  connect(&link_, &LinkController::healthChanged, this, &RecordingUi::onHealth);
  connect(&session_, &SessionController::mappingParametersChanged, this,
          &RecordingUi::onMappingParametersChanged);
  recorder_check_.setInterval(kRecorderCheck_ms);
  connect(&recorder_check_, &QTimer::timeout, this, &RecordingUi::checkRecorder);
  drain_check_.setInterval(kDrainPoll_ms);
  connect(&drain_check_, &QTimer::timeout, this, &RecordingUi::checkDrained);
}

RecordingUi::~RecordingUi() {
  // The window is being destroyed (it owns this object): do not put the previous robot back,
  // since installing a robot signals the window's own slots, which are gone by now (that
  // crashed). The replayed robot keeps its IoThread alive through its handle; the session that
  // owns it is destroyed after the window.
  drain_check_.stop();
  if (player_ != nullptr) {
    if (bar_)
      bar_->disconnect(player_);
    delete player_;
    player_ = nullptr;
  }
  saved_factory_ = {};
  stopRecording();
}

QString RecordingUi::defaultRecordingsDir(const QString& settings_file) {
  QString base;
  if (!settings_file.isEmpty())
    base = QFileInfo(settings_file).absolutePath();
  else if (const QByteArray env = qgetenv("IRGS_SETTINGS_FILE"); !env.isEmpty())
    base = QFileInfo(QString::fromLocal8Bit(env)).absolutePath();
  else
    base = QStandardPaths::writableLocation(QStandardPaths::AppLocalDataLocation);
  return QDir(base).filePath(QStringLiteral("recordings"));
}

QString RecordingUi::newRecordingPath(const QString& dir) {
  const QString stem = QStringLiteral("session-") +
                       QDateTime::currentDateTime().toString(QStringLiteral("yyyyMMdd-HHmmss"));
  const QString suffix = QString::fromLatin1(recording::kFileSuffix);
  QString path = QDir(dir).filePath(stem + suffix);
  for (int n = 2; QFileInfo::exists(path); ++n)
    path = QDir(dir).filePath(stem + QStringLiteral("-%1").arg(n) + suffix);
  return path;
}

QString RecordingUi::startRecording(const QString& path) {
  stopRecording();
  const QFileInfo info(path);
  if (!QDir().mkpath(info.absolutePath()))
    return tr("cannot create the folder %1").arg(info.absolutePath());
  std::map<std::string, std::string> meta{
      {"program", "irgs " IRGS_VERSION},
      {"robot", session_.profile().name},
      {"map", session_.worldSource().toStdString()},
  };
  if (!robot_file_.isEmpty())
    meta["robot_file"] = QFileInfo(robot_file_).absoluteFilePath().toStdString();
  for (const auto& [key, value] : mappingParameterMeta())
    meta[key] = value;
  recording::SessionRecorder::OpenResult opened =
      recording::SessionRecorder::create(info.absoluteFilePath().toStdString(), meta);
  if (!opened.recorder)
    return QString::fromStdString(opened.error);
  recorder_ = std::move(opened.recorder);
  {
    const std::lock_guard lock(tap_target_->mutex);
    tap_target_->tap = recorder_->tap();
  }
  last_recorder_error_.clear();
  last_command_ = session_.command();
  recorder_check_.start();
  session_.report(EventLevel::kInfo,
                  tr("Recording this session to %1").arg(info.absoluteFilePath()));
  return {};
}

std::map<std::string, std::string> RecordingUi::mappingParameterMeta() const {
  // The re-run's "recorded parameters" (app/recording/rerun_parameters.hpp): what this session
  // maps with. The sensor model is the code's default in the GUI, so it needs no entry.
  const std::string prefix = recording::kRerunMetaPrefix;
  const std::optional<double> valid = session_.sonarValidDistance_m();
  return {{prefix + "grid_resolution_m",
           QString::number(session_.grid().resolution_m(), 'g', 10).toStdString()},
          {prefix + "sonar_valid_distance_m",
           QString::number(valid.value_or(0.0), 'g', 10).toStdString()}};
}

void RecordingUi::onMappingParametersChanged() {
  if (!recorder_ || replaying())
    return;
  // The meta holds the parameters last in force; the change is also on the timeline.
  std::string text = "Mapping parameters:";
  for (const auto& [key, value] : mappingParameterMeta()) {
    recorder_->setMeta(key, value);
    text += " " + key.substr(std::string(recording::kRerunMetaPrefix).size()) + "=" + value;
  }
  recorder_->recordEvent("info", text);
}

void RecordingUi::stopRecording() {
  if (!recorder_)
    return;
  {
    const std::lock_guard lock(tap_target_->mutex);
    tap_target_->tap = {};
  }
  recorder_check_.stop();
  recorder_.reset();  // commits what is queued
}

void RecordingUi::checkRecorder() {
  if (!recorder_)
    return;
  const recording::RecorderStats stats = recorder_->stats();
  if (!stats.last_error.empty() && stats.last_error != last_recorder_error_) {
    last_recorder_error_ = stats.last_error;
    session_.report(EventLevel::kError, tr("Recording: %1 (%2 rows lost)")
                                            .arg(QString::fromStdString(stats.last_error))
                                            .arg(stats.dropped_rows));
  }
}

void RecordingUi::onConsole(EventLevel level, const QString& text) {
  if (recorder_)
    recorder_->recordEvent(levelName(level), text.toStdString());
}

void RecordingUi::onHealth(const widgets::LinkHealth& health) {
  if (health.crc_errors > last_crc_errors_ && recorder_ && !replaying())
    recorder_->recordEvent("link", "CRC errors: +" +
                                       std::to_string(health.crc_errors - last_crc_errors_) + " (" +
                                       std::to_string(health.crc_errors) + " in total)");
  last_crc_errors_ = health.crc_errors;
}

void RecordingUi::onTicked() {
  if (!recorder_)
    return;
  const VelocityCommand& command = session_.command();
  if (command.linear_mps == last_command_.linear_mps &&
      command.angular_radps == last_command_.angular_radps)
    return;
  last_command_ = command;
  const bool zero = command.linear_mps == 0.0 && command.angular_radps == 0.0;
  recorder_->recordCommand(zero ? std::string("stop")
                                : QStringLiteral("drive %1 %2")
                                      .arg(command.linear_mps, 0, 'f', 3)
                                      .arg(command.angular_radps, 0, 'f', 3)
                                      .toStdString());
}

void RecordingUi::onRobotState(const TelemetrySample& sample) {
  if (expect_initial_sample_) {
    // installRobot's synthetic start-pose sample: it carries the new robot's time zero.
    expect_initial_sample_ = false;
    robot_epoch_s_ = sample.time_s;
    return;
  }
  if (collect_trajectory_)
    trajectory_.push_back({sample.time_s - robot_epoch_s_, sample.odometry_pose});
  if (recorder_ && sample.true_pose && !replaying())
    recorder_->recordTruth(sample.true_pose->x, sample.true_pose->y, sample.true_pose->theta);
}

void RecordingUi::onSampleIntegrated(const TelemetrySample& sample) {
  // A simulator session is recorded as the bytes a robot running the IRGS firmware would have
  // sent for its samples, so it replays and re-runs through the link path like a robot's.
  if (!recorder_ || replaying() || session_.simulationControl() == nullptr)
    return;
  if (!simulator_frames_) {
    simulator_frames_.emplace(session_.profile());
    recorder_->setMeta("telemetry_source", "simulator (IRGS firmware compact streams)");
  }
  simulator_frames_->write(sample, frame_buffer_);
  if (frame_buffer_.empty())
    return;
  recorder_->recordFrame(comms::TapDirection::kReceived, std::chrono::steady_clock::now(),
                         frame_buffer_);
  frame_buffer_.clear();
}

void RecordingUi::chooseAndOpenReplay() {
  const QString dir = recorder_
                          ? QFileInfo(QString::fromStdString(recorder_->path())).absolutePath()
                          : defaultRecordingsDir(QString());
  const QString path = QFileDialog::getOpenFileName(
      &window_, tr("Open Recording"), dir,
      tr("IRGS recordings (*%1);;All files (*)").arg(QString::fromLatin1(recording::kFileSuffix)));
  if (path.isEmpty())
    return;
  const QString problem = openReplay(path);
  if (!problem.isEmpty())
    session_.report(EventLevel::kError, tr("Cannot replay %1: %2").arg(path, problem));
}

QString RecordingUi::openReplay(const QString& path, double speed) {
  recording::LoadResult loaded = recording::loadRecording(path.toStdString());
  if (!loaded.recording)
    return QString::fromStdString(loaded.error);
  for (const std::string& warning : loaded.warnings)
    session_.report(EventLevel::kWarning, QString::fromStdString(warning));
  if (loaded.recording->receivedFrameCount() == 0)
    return tr(
        "the recording holds no received link bytes (no robot link and no simulator sample "
        "in it, or made before simulator sessions were recorded as frames)");
  auto recording = std::make_shared<const recording::Recording>(std::move(*loaded.recording));

  if (replaying())
    closeReplay();
  if (!io_)
    io_ = std::make_shared<comms::IoThread>();
  auto feed = std::make_shared<comms::ReplayFeed>();
  const std::string name = QFileInfo(path).fileName().toStdString();
  comms::LinkUrl url;
  url.scheme = comms::LinkScheme::kTcp;
  url.host = "replay";
  url.options["file"] = name;
  RobotFactory factory = [io = io_, feed, url, name](
                             const WorldMap&,
                             const RobotProfile& profile) -> std::unique_ptr<Robot> {
    comms::RemoteRobotConfig config;
    config.mavlink.link.make_transport = comms::replayTransportMaker(feed, "replay " + name);
    config.mavlink.link.session.timeout_s = kReplayHeartbeatTimeout_s;
    config.mavlink.messages = guiMessageSampling();
    config.name = "replay://" + name;
    comms::OpenRemoteRobotResult opened =
        comms::openRemoteRobot(io, url, profile, std::move(config));
    if (!opened.robot)
      throw std::runtime_error(opened.error);
    return std::move(opened.robot);
  };
  RobotFactory previous = session_.robotFactory();
  try {
    installing_ = true;
    session_.setRobotFactory(std::move(factory));
    installing_ = false;
  } catch (const std::exception& e) {
    installing_ = false;
    return QString::fromUtf8(e.what());
  }
  saved_factory_ = std::move(previous);
  feed_ = feed;
  session_.resetGrid();

  player_ = new recording::ReplayPlayer(recording, feed_, this);
  player_->setSpeed(speed);
  connect(player_, &recording::ReplayPlayer::positionChanged, bar_,
          &widgets::ReplayBar::setPosition);
  connect(player_, &recording::ReplayPlayer::playingChanged, bar_, &widgets::ReplayBar::setPlaying);
  connect(player_, &recording::ReplayPlayer::speedChanged, bar_, &widgets::ReplayBar::setSpeed);
  connect(bar_, &widgets::ReplayBar::playToggled, player_, &recording::ReplayPlayer::setPlaying);
  connect(bar_, &widgets::ReplayBar::stepRequested, player_, &recording::ReplayPlayer::step);
  connect(bar_, &widgets::ReplayBar::speedChosen, player_, &recording::ReplayPlayer::setSpeed);
  connect(bar_, &widgets::ReplayBar::seekRequested, player_, &recording::ReplayPlayer::seek);
  connect(player_, &recording::ReplayPlayer::restartRequested, this, [this] {
    drain_check_.stop();
    installing_ = true;
    session_.resetRobotToStart();  // a fresh LinkedRobot on a fresh replay transport
    installing_ = false;
    session_.resetGrid();
  });
  connect(player_, &recording::ReplayPlayer::finished, this, [this] {
    drain_stable_polls_ = 0;
    drain_samples_ = 0;
    drain_check_.start();
  });
  bar_->setRecordingName(QString::fromStdString(name));
  bar_->setDuration(player_->duration_s());
  bar_->setMarks(timelineMarks(*recording));
  bar_->setSpeed(player_->speed());
  bar_->setPosition(0.0);
  dock_->show();
  session_.report(EventLevel::kInfo, tr("Replaying %1: %2 s, %3 received chunks, %4 events")
                                         .arg(QString::fromStdString(name))
                                         .arg(player_->duration_s(), 0, 'f', 1)
                                         .arg(player_->chunkCount())
                                         .arg(recording->events.size()));
  player_->startTimer();
  player_->play();
  return {};
}

void RecordingUi::onRobotReplacedElsewhere() {
  // Someone else replaced the replayed robot: the Reset action rebuilt it from our factory (the
  // new one has not seen the bytes so far: replay from the start), or a link or the simulator
  // took over (the replay ends where it is, the new robot stays).
  const comms::RemoteRobot* remote = link_.remote();
  if (remote != nullptr && remote->url().rfind("replay://", 0) == 0) {
    player_->seek(0.0);
    return;
  }
  saved_factory_ = {};
  closeReplay();
}

void RecordingUi::checkDrained() {
  if (!player_ || !feed_) {
    drain_check_.stop();
    return;
  }
  std::uint64_t samples = 0;
  if (const comms::RemoteRobot* remote = link_.remote())
    samples = remote->telemetryRates().samples;
  const bool delivered = feed_->deliveredBytes() + feed_->droppedBytes() >= feed_->pushedBytes();
  if (delivered && session_.pendingSamples() == 0 && samples == drain_samples_) {
    ++drain_stable_polls_;
  } else {
    drain_stable_polls_ = 0;
  }
  drain_samples_ = samples;
  if (drain_stable_polls_ < kDrainStablePolls)
    return;
  drain_check_.stop();
  session_.report(
      EventLevel::kInfo,
      tr("Replay finished: %1 received chunks, %2 samples").arg(player_->chunksFed()).arg(samples));
  emit replayDrained();
}

void RecordingUi::closeReplay() {
  if (!player_)
    return;
  drain_check_.stop();
  if (bar_)
    bar_->disconnect(player_);
  delete player_;
  player_ = nullptr;
  if (dock_)
    dock_->hide();
  if (saved_factory_) {
    try {
      const QScopedValueRollback<bool> installing(installing_, true);
      session_.setRobotFactory(saved_factory_);
    } catch (const std::exception& e) {
      session_.report(
          EventLevel::kError,
          tr("Cannot restore the robot after the replay: %1").arg(QString::fromUtf8(e.what())));
    }
    session_.resetGrid();
  }
  saved_factory_ = {};
  feed_.reset();
  session_.report(EventLevel::kInfo, tr("Replay closed"));
}

}  // namespace irgs::gui
