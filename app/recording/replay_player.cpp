#include "app/recording/replay_player.hpp"

#include "comms/link/frame_tap.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace irgs::recording {

ReplayPlayer::ReplayPlayer(std::shared_ptr<const Recording> recording,
                           std::shared_ptr<comms::ReplayFeed> feed, QObject* parent)
    : QObject(parent), recording_(std::move(recording)), feed_(std::move(feed)) {
  if (!recording_ || !feed_)
    throw std::invalid_argument("ReplayPlayer: null recording or feed");
  for (const RecordedFrame& frame : recording_->frames) {
    if (frame.dir == static_cast<std::uint8_t>(comms::TapDirection::kReceived))
      received_.push_back(&frame);
  }
  duration_s_ = recording_->duration_s();
  timer_.setInterval(kTimerInterval_ms);
  connect(&timer_, &QTimer::timeout, this, &ReplayPlayer::onTimer);
}

void ReplayPlayer::startTimer() {
  wall_.start();
  timer_.start();
}

void ReplayPlayer::onTimer() {
  const double elapsed_s = static_cast<double>(wall_.nsecsElapsed()) * 1e-9;
  wall_.restart();
  // A stalled GUI (a modal dialog) must not turn into a burst of recording time.
  advance(std::min(elapsed_s, 0.25));
}

void ReplayPlayer::play() {
  setPlaying(true);
}

void ReplayPlayer::pause() {
  setPlaying(false);
}

void ReplayPlayer::setPlaying(bool playing) {
  if (seeking()) {
    resume_after_catch_up_ = playing;
    return;
  }
  if (playing && atEnd())
    return;
  if (playing == playing_)
    return;
  playing_ = playing;
  emit playingChanged(playing_);
}

void ReplayPlayer::setSpeed(double speed) {
  if (!std::isfinite(speed))
    return;
  const double clamped = std::clamp(speed, kMinSpeed, kMaxSpeed);
  if (clamped == speed_)
    return;
  speed_ = clamped;
  emit speedChanged(speed_);
}

void ReplayPlayer::seek(double position_s) {
  if (!std::isfinite(position_s))
    return;
  const double target = std::clamp(position_s, 0.0, duration_s_);
  if (!seeking())
    resume_after_catch_up_ = playing_;
  if (target < position_s_) {
    emit restartRequested();
    position_s_ = 0.0;
    next_ = 0;
  }
  if (playing_) {
    playing_ = false;
    emit playingChanged(false);
  }
  catch_up_target_s_ = target;
  advance(0.0);  // the first catch-up slice at once (a short seek completes here)
}

void ReplayPlayer::step() {
  if (seeking())
    return;
  setPlaying(false);
  if (next_ >= received_.size())
    return;
  feedUpTo(received_[next_]->t_s);
  emit positionChanged(position_s_);
}

void ReplayPlayer::advance(double wall_elapsed_s) {
  if (catch_up_target_s_) {
    const double target = std::min(*catch_up_target_s_, position_s_ + kCatchUp_s);
    feedUpTo(target);
    if (position_s_ >= *catch_up_target_s_) {
      catch_up_target_s_.reset();
      if (resume_after_catch_up_)
        setPlaying(true);
    }
    emit positionChanged(position_s_);
    return;
  }
  if (!playing_ || !(wall_elapsed_s > 0.0) || !std::isfinite(wall_elapsed_s))
    return;
  feedUpTo(std::min(duration_s_, position_s_ + wall_elapsed_s * speed_));
  emit positionChanged(position_s_);
  if (atEnd()) {
    playing_ = false;
    emit playingChanged(false);
    emit finished();
  }
}

void ReplayPlayer::feedUpTo(double position_s) {
  while (next_ < received_.size() && received_[next_]->t_s <= position_s) {
    feed_->push(received_[next_]->bytes);
    ++next_;
  }
  position_s_ = std::max(position_s_, position_s);
}

}  // namespace irgs::recording
