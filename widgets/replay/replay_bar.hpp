#pragma once
// The replay bar (docs/gui.md, "Recording and replay"): play/pause, single step, speed
// x0.25..x16, a timeline to seek on with the recording's events marked (link loss, errors,
// mode changes), and the position / duration. It only shows and asks: the application's replay
// player does the work and reports back through setPosition/setPlaying/setSpeed.

#include <QString>
#include <QWidget>
#include <vector>

class QComboBox;
class QLabel;
class QToolButton;

namespace irgs::widgets {

enum class ReplayMarkKind { kInfo, kWarning, kError };

struct ReplayMark {
  double t_s = 0.0;
  ReplayMarkKind kind = ReplayMarkKind::kInfo;
  QString text;  // tooltip
};

// The timeline: a track with marks and a cursor; click or drag to seek.
class ReplayTimeline : public QWidget {
  Q_OBJECT

 public:
  explicit ReplayTimeline(QWidget* parent = nullptr);
  void setDuration(double duration_s);
  void setPosition(double position_s);
  void setMarks(std::vector<ReplayMark> marks);
  double duration_s() const { return duration_s_; }
  double position_s() const { return position_s_; }
  const std::vector<ReplayMark>& marks() const { return marks_; }
  // Recording time under the widget x coordinate `x` (clamped to the track).
  double timeAt(int x) const;
  QSize sizeHint() const override;

 signals:
  void seekRequested(double position_s);

 protected:
  void paintEvent(QPaintEvent* event) override;
  void mousePressEvent(QMouseEvent* event) override;
  void mouseMoveEvent(QMouseEvent* event) override;
  bool event(QEvent* event) override;  // tooltips of marks

 private:
  int xAt(double t_s) const;
  const ReplayMark* markNear(int x) const;

  double duration_s_ = 0.0;
  double position_s_ = 0.0;
  std::vector<ReplayMark> marks_;
};

class ReplayBar : public QWidget {
  Q_OBJECT

 public:
  // The speeds offered, x0.25 .. x16.
  static const std::vector<double>& speeds();

  explicit ReplayBar(QWidget* parent = nullptr);

  void setRecordingName(const QString& name);
  void setDuration(double duration_s);
  void setMarks(std::vector<ReplayMark> marks);
  ReplayTimeline& timeline() const { return *timeline_; }
  QToolButton& playButton() const { return *play_; }
  QToolButton& stepButton() const { return *step_; }
  QComboBox& speedBox() const { return *speed_; }
  QString positionText() const;

 public slots:
  void setPosition(double position_s);
  void setPlaying(bool playing);
  void setSpeed(double speed);  // selects the nearest offered speed

 signals:
  void playToggled(bool play);
  void stepRequested();
  void speedChosen(double speed);
  void seekRequested(double position_s);
  void closeRequested();

 private:
  QLabel* name_ = nullptr;
  QToolButton* play_ = nullptr;
  QToolButton* step_ = nullptr;
  QComboBox* speed_ = nullptr;
  ReplayTimeline* timeline_ = nullptr;
  QLabel* time_ = nullptr;
  QToolButton* close_ = nullptr;
  double duration_s_ = 0.0;
  bool playing_ = false;
};

}  // namespace irgs::widgets
