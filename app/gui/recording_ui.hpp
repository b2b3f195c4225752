#pragma once
// Session recording and replay in the window (docs/gui.md, "Recording and replay"; the work is
// in app/recording). Recording: every MAVLink byte the robot link receives and sends (through
// the link's frame tap), the console lines, the user's drive commands, CRC-error bursts and, in
// simulator mode, the ground-truth pose, into one SQLite file per session that continues across
// reconnects and robot switches. Replay: File > Open Recording... makes a LinkedRobot on a
// replay transport the session's robot, so the recording plays through the same decoder, link
// session and telemetry path as a live robot; the replay bar (widgets/replay) plays, pauses,
// steps, changes speed and seeks.

#include <QDockWidget>
#include <QObject>
#include <QPointer>
#include <QString>
#include <QTimer>
#include <map>
#include <memory>
#include <optional>
#include <vector>

#include "app/gui/session_controller.hpp"
#include "app/recording/session_dump.hpp"
#include "comms/robot/telemetry_frame_writer.hpp"
#include "widgets/replay/replay_bar.hpp"

class QAction;
class QMainWindow;

namespace irgs::comms {
class IoThread;
class ReplayFeed;
}  // namespace irgs::comms

namespace irgs::recording {
class ReplayPlayer;
class SessionRecorder;
struct Recording;
}  // namespace irgs::recording

namespace irgs::widgets {
struct LinkHealth;
}  // namespace irgs::widgets

namespace irgs::gui {

class LinkController;

class RecordingUi : public QObject {
  Q_OBJECT

 public:
  // Heartbeat timeout of a replayed link: a paused replay must not read as a lost link (the
  // recording's own link losses are in its events).
  static constexpr double kReplayHeartbeatTimeout_s = 1e6;

  // Adds File > Open Recording... to the window's File menu and a hidden replay bar dock.
  RecordingUi(SessionController& session, LinkController& link, QMainWindow& window);
  ~RecordingUi() override;

  // Where recordings go by default: "recordings" beside a custom settings file (tests and
  // separate profiles keep their own), else the user's application data folder.
  static QString defaultRecordingsDir(const QString& settings_file);
  // A new file name in `dir`: session-YYYYMMDD-HHMMSS.irgsrec (with -2, -3 ... if taken).
  static QString newRecordingPath(const QString& dir);

  // Starts recording into the new file `path` (its folder is created). Empty on success, else
  // why not (the session then runs unrecorded).
  QString startRecording(const QString& path);
  // The robot profile file of the session, written to the recording's meta ("robot_file") so a
  // re-run finds the same profile. Set before startRecording.
  void setRobotFile(const QString& path) { robot_file_ = path; }
  void stopRecording();
  recording::SessionRecorder* recorder() const { return recorder_.get(); }

  // Replays `path` as the session's robot. Empty on success, else why not (session unchanged).
  QString openReplay(const QString& path, double speed = 1.0);
  // Back to the robot the session had before the replay.
  void closeReplay();
  bool replaying() const { return player_ != nullptr; }
  recording::ReplayPlayer* player() const { return player_; }
  widgets::ReplayBar& bar() const { return *bar_; }
  QAction* openRecordingAction() const { return open_action_; }

  // Poses shown since the robot was last replaced, time relative to that robot's start (what
  // --trajectory-out writes).
  // Collected only after setCollectTrajectory(true) (off by default: it grows with the session).
  const std::vector<recording::TrajectoryPoint>& trajectory() const { return trajectory_; }
  void setCollectTrajectory(bool on) { collect_trajectory_ = on; }

 signals:
  // The replay reached its end and everything fed was decoded and integrated.
  void replayDrained();

 private:
  void chooseAndOpenReplay();
  void onRobotState(const TelemetrySample& sample);
  void onSampleIntegrated(const TelemetrySample& sample);
  void onTicked();
  void onConsole(EventLevel level, const QString& text);
  void onHealth(const widgets::LinkHealth& health);
  void checkDrained();
  void onRobotReplacedElsewhere();
  void checkRecorder();
  std::map<std::string, std::string> mappingParameterMeta() const;
  void onMappingParametersChanged();

  SessionController& session_;
  LinkController& link_;
  QMainWindow& window_;
  QAction* open_action_ = nullptr;
  // Children of the window, which may delete them before this object.
  QPointer<QDockWidget> dock_;
  QPointer<widgets::ReplayBar> bar_;

  std::unique_ptr<recording::SessionRecorder> recorder_;
  struct TapTarget;
  std::shared_ptr<TapTarget> tap_target_;  // what LinkController's tap forwards to
  QTimer recorder_check_;
  std::string last_recorder_error_;
  VelocityCommand last_command_;
  std::uint64_t last_crc_errors_ = 0;

  std::shared_ptr<comms::IoThread> io_;
  std::shared_ptr<comms::ReplayFeed> feed_;
  recording::ReplayPlayer* player_ = nullptr;
  RobotFactory saved_factory_;
  QTimer drain_check_;
  int drain_stable_polls_ = 0;
  std::uint64_t drain_samples_ = 0;

  std::vector<recording::TrajectoryPoint> trajectory_;
  double robot_epoch_s_ = 0.0;
  // Simulator mode: the samples as a robot's frames (reset with each new robot).
  std::optional<comms::TelemetryFrameWriter> simulator_frames_;
  std::vector<std::uint8_t> frame_buffer_;
  bool expect_initial_sample_ = false;
  bool collect_trajectory_ = false;
  bool installing_ = false;  // we are replacing the session's robot ourselves
  QString robot_file_;
};

}  // namespace irgs::gui
