#include "widgets/replay/replay_bar.hpp"

#include <QComboBox>
#include <QHBoxLayout>
#include <QHelpEvent>
#include <QLabel>
#include <QMouseEvent>
#include <QPainter>
#include <QSignalBlocker>
#include <QStyle>
#include <QToolButton>
#include <QToolTip>
#include <algorithm>
#include <cmath>

namespace irgs::widgets {

namespace {

constexpr int kMargin_px = 6;       // track inset at both ends
constexpr int kMarkPickRadius = 4;  // px around a mark that shows its tooltip

QString clockText(double t_s) {
  const int total = static_cast<int>(std::floor(std::max(0.0, t_s)));
  const int tenths = static_cast<int>(std::floor((std::max(0.0, t_s) - total) * 10.0));
  return QStringLiteral("%1:%2.%3")
      .arg(total / 60)
      .arg(total % 60, 2, 10, QLatin1Char('0'))
      .arg(tenths);
}

QColor markColour(ReplayMarkKind kind) {
  switch (kind) {
    case ReplayMarkKind::kError:
      return QColor(0xd0, 0x30, 0x30);
    case ReplayMarkKind::kWarning:
      return QColor(0xe0, 0x90, 0x20);
    case ReplayMarkKind::kInfo:
      break;
  }
  return QColor(0x40, 0x80, 0xc0);
}

}  // namespace

ReplayTimeline::ReplayTimeline(QWidget* parent) : QWidget(parent) {
  setMinimumWidth(200);
  setMouseTracking(false);
  setToolTip(tr("Click or drag to seek"));
}

QSize ReplayTimeline::sizeHint() const {
  return {400, 24};
}

void ReplayTimeline::setDuration(double duration_s) {
  duration_s_ = std::isfinite(duration_s) ? std::max(0.0, duration_s) : 0.0;
  update();
}

void ReplayTimeline::setPosition(double position_s) {
  if (!std::isfinite(position_s))
    return;
  position_s_ = std::clamp(position_s, 0.0, duration_s_);
  update();
}

void ReplayTimeline::setMarks(std::vector<ReplayMark> marks) {
  marks_ = std::move(marks);
  update();
}

int ReplayTimeline::xAt(double t_s) const {
  const int w = std::max(1, width() - 2 * kMargin_px);
  if (duration_s_ <= 0.0)
    return kMargin_px;
  return kMargin_px + static_cast<int>(std::lround(std::clamp(t_s / duration_s_, 0.0, 1.0) * w));
}

double ReplayTimeline::timeAt(int x) const {
  const int w = std::max(1, width() - 2 * kMargin_px);
  const double f = std::clamp(static_cast<double>(x - kMargin_px) / w, 0.0, 1.0);
  return f * duration_s_;
}

const ReplayMark* ReplayTimeline::markNear(int x) const {
  const ReplayMark* best = nullptr;
  int best_d = kMarkPickRadius + 1;
  for (const ReplayMark& mark : marks_) {
    const int d = std::abs(xAt(mark.t_s) - x);
    if (d < best_d) {
      best_d = d;
      best = &mark;
    }
  }
  return best;
}

void ReplayTimeline::paintEvent(QPaintEvent*) {
  QPainter p(this);
  p.setRenderHint(QPainter::Antialiasing, false);
  const int mid = height() / 2;
  p.fillRect(QRect(kMargin_px, mid - 2, width() - 2 * kMargin_px, 4), palette().mid());
  p.fillRect(QRect(kMargin_px, mid - 2, xAt(position_s_) - kMargin_px, 4), palette().highlight());
  for (const ReplayMark& mark : marks_) {
    p.setPen(QPen(markColour(mark.kind), 2));
    const int x = xAt(mark.t_s);
    p.drawLine(x, 2, x, mid - 4);
  }
  p.setPen(QPen(palette().text().color(), 1));
  p.setBrush(palette().button());
  const int cx = xAt(position_s_);
  p.drawRect(QRect(cx - 3, mid - 7, 6, 14));
}

void ReplayTimeline::mousePressEvent(QMouseEvent* event) {
  if (event->button() == Qt::LeftButton && duration_s_ > 0.0)
    emit seekRequested(timeAt(static_cast<int>(event->position().x())));
}

void ReplayTimeline::mouseMoveEvent(QMouseEvent* event) {
  if ((event->buttons() & Qt::LeftButton) && duration_s_ > 0.0)
    emit seekRequested(timeAt(static_cast<int>(event->position().x())));
}

bool ReplayTimeline::event(QEvent* event) {
  if (event->type() == QEvent::ToolTip) {
    auto* help = static_cast<QHelpEvent*>(event);
    if (const ReplayMark* mark = markNear(help->pos().x())) {
      QToolTip::showText(help->globalPos(),
                         QStringLiteral("%1  %2").arg(clockText(mark->t_s), mark->text), this);
      return true;
    }
  }
  return QWidget::event(event);
}

const std::vector<double>& ReplayBar::speeds() {
  static const std::vector<double> kSpeeds{0.25, 0.5, 1.0, 2.0, 4.0, 8.0, 16.0};
  return kSpeeds;
}

ReplayBar::ReplayBar(QWidget* parent) : QWidget(parent) {
  auto* layout = new QHBoxLayout(this);
  layout->setContentsMargins(4, 2, 4, 2);
  name_ = new QLabel(this);
  play_ = new QToolButton(this);
  play_->setToolTip(tr("Play / pause the replay"));
  step_ = new QToolButton(this);
  step_->setIcon(style()->standardIcon(QStyle::SP_MediaSeekForward));
  step_->setToolTip(tr("Single step: the next received chunk of the recording"));
  speed_ = new QComboBox(this);
  for (double s : speeds())
    speed_->addItem(QStringLiteral("x%1").arg(s), s);
  speed_->setToolTip(tr("Replay speed"));
  timeline_ = new ReplayTimeline(this);
  time_ = new QLabel(this);
  time_->setMinimumWidth(
      time_->fontMetrics().horizontalAdvance(QStringLiteral("00:00.0 / 00:00.0")));
  close_ = new QToolButton(this);
  close_->setIcon(style()->standardIcon(QStyle::SP_DialogCloseButton));
  close_->setToolTip(tr("Close the replay (back to the simulator)"));
  layout->addWidget(name_);
  layout->addWidget(play_);
  layout->addWidget(step_);
  layout->addWidget(speed_);
  layout->addWidget(timeline_, 1);
  layout->addWidget(time_);
  layout->addWidget(close_);

  setSpeed(1.0);
  setPlaying(false);
  setPosition(0.0);
  connect(play_, &QToolButton::clicked, this, [this] { emit playToggled(!playing_); });
  connect(step_, &QToolButton::clicked, this, &ReplayBar::stepRequested);
  connect(speed_, &QComboBox::currentIndexChanged, this,
          [this](int index) { emit speedChosen(speed_->itemData(index).toDouble()); });
  connect(timeline_, &ReplayTimeline::seekRequested, this, &ReplayBar::seekRequested);
  connect(close_, &QToolButton::clicked, this, &ReplayBar::closeRequested);
}

void ReplayBar::setRecordingName(const QString& name) {
  name_->setText(name);
}

void ReplayBar::setDuration(double duration_s) {
  duration_s_ = std::isfinite(duration_s) ? std::max(0.0, duration_s) : 0.0;
  timeline_->setDuration(duration_s_);
  setPosition(timeline_->position_s());
}

void ReplayBar::setMarks(std::vector<ReplayMark> marks) {
  timeline_->setMarks(std::move(marks));
}

QString ReplayBar::positionText() const {
  return time_->text();
}

void ReplayBar::setPosition(double position_s) {
  timeline_->setPosition(position_s);
  time_->setText(
      QStringLiteral("%1 / %2").arg(clockText(timeline_->position_s()), clockText(duration_s_)));
}

void ReplayBar::setPlaying(bool playing) {
  playing_ = playing;
  play_->setIcon(style()->standardIcon(playing ? QStyle::SP_MediaPause : QStyle::SP_MediaPlay));
  play_->setText(playing ? tr("Pause") : tr("Play"));
}

void ReplayBar::setSpeed(double speed) {
  if (!std::isfinite(speed))
    return;
  int best = 0;
  for (int i = 1; i < speed_->count(); ++i) {
    if (std::abs(std::log(speeds()[static_cast<std::size_t>(i)] / speed)) <
        std::abs(std::log(speeds()[static_cast<std::size_t>(best)] / speed)))
      best = i;
  }
  const QSignalBlocker block(speed_);
  speed_->setCurrentIndex(best);
}

}  // namespace irgs::widgets
