#pragma once
// Plays a recording's received link bytes into a ReplayFeed with their recorded timing, so a
// LinkedRobot on a replay transport sees them as it saw them live (docs/gui.md, "Recording and
// replay"). Position is recording time in seconds (0 = start of the recording).
//
// play/pause, speed kMinSpeed..kMaxSpeed, seek, single step (to the next received chunk).
// Seeking backwards cannot un-feed bytes: the player emits restartRequested() (the owner builds
// a fresh robot on a fresh replay transport and clears the map) and re-feeds from the start up
// to the target fast, kCatchUp_s of recording per advance(), then goes on as before.
//
// Time: a QTimer calls advance() with the wall time elapsed; tests call advance() themselves.

#include "app/recording/recording_format.hpp"
#include "comms/transport/replay_transport.hpp"

#include <QElapsedTimer>
#include <QObject>
#include <QTimer>
#include <memory>
#include <optional>

namespace irgs::recording {

class ReplayPlayer : public QObject {
  Q_OBJECT

 public:
  static constexpr double kMinSpeed = 0.25;
  static constexpr double kMaxSpeed = 16.0;
  static constexpr double kCatchUp_s = 2.0;  // recording seconds fed per advance() when seeking
  static constexpr int kTimerInterval_ms = 10;

  // Throws std::invalid_argument for a null recording or feed.
  ReplayPlayer(std::shared_ptr<const Recording> recording, std::shared_ptr<comms::ReplayFeed> feed,
               QObject* parent = nullptr);

  const Recording& recording() const { return *recording_; }
  double duration_s() const { return duration_s_; }
  double position_s() const { return position_s_; }
  bool playing() const { return playing_; }
  double speed() const { return speed_; }
  bool atEnd() const { return next_ >= received_.size() && position_s_ >= duration_s_; }
  bool seeking() const { return catch_up_target_s_.has_value(); }
  std::size_t chunksFed() const { return next_; }
  std::size_t chunkCount() const { return received_.size(); }

  // Starts/stops the wall-clock timer (the GUI); tests drive advance() directly.
  void startTimer();

 public slots:
  void play();
  void pause();
  void setPlaying(bool playing);
  void setSpeed(double speed);   // clamped to [kMinSpeed, kMaxSpeed]; non-finite ignored
  void seek(double position_s);  // clamped to [0, duration]
  void step();                   // pauses, then feeds the next received chunk
  void advance(double wall_elapsed_s);

 signals:
  void positionChanged(double position_s);
  void playingChanged(bool playing);
  void speedChanged(double speed);
  void finished();          // the end of the recording was reached while playing
  void restartRequested();  // rebuild the robot and clear the map: re-feeding from the start

 private:
  void feedUpTo(double position_s);
  void onTimer();

  std::shared_ptr<const Recording> recording_;
  std::shared_ptr<comms::ReplayFeed> feed_;
  std::vector<const RecordedFrame*> received_;  // dir 0 only, in time order
  double duration_s_ = 0.0;
  double position_s_ = 0.0;
  std::size_t next_ = 0;  // first chunk not fed yet
  bool playing_ = false;
  double speed_ = 1.0;
  std::optional<double> catch_up_target_s_;
  bool resume_after_catch_up_ = false;
  QTimer timer_;
  QElapsedTimer wall_;
};

}  // namespace irgs::recording
