#include "widgets/console/console_widget.hpp"

#include <QApplication>
#include <QCheckBox>
#include <QClipboard>
#include <QFontDatabase>
#include <QHBoxLayout>
#include <QLineEdit>
#include <QPlainTextEdit>
#include <QScrollBar>
#include <QSyntaxHighlighter>
#include <QTimer>
#include <QToolButton>
#include <QVBoxLayout>
#include <cmath>

namespace irgs::widgets {
namespace {

// Column layout of a line: "[" time "s] " tag "  " text. The tag column is fixed-width so the
// highlighter can find it without parsing.
constexpr int kTagWidth = 6;

const char* levelTag(ConsoleLevel level) {
  switch (level) {
    case ConsoleLevel::kInfo:
      return "INFO";
    case ConsoleLevel::kWarning:
      return "WARN";
    case ConsoleLevel::kError:
      return "ERROR";
    case ConsoleLevel::kSensor:
      return "SENSOR";
  }
  return "?";
}

std::size_t levelIndex(ConsoleLevel level) {
  return static_cast<std::size_t>(level);
}

QColor levelColour(ConsoleLevel level) {
  switch (level) {
    case ConsoleLevel::kInfo:
      return {33, 37, 41};
    case ConsoleLevel::kWarning:
      return {176, 96, 0};
    case ConsoleLevel::kError:
      return {198, 40, 40};
    case ConsoleLevel::kSensor:
      return {0, 121, 107};
  }
  return {33, 37, 41};
}

}  // namespace

// Colours each line by the level tag it carries (lines are formatted by formatLine()).
class ConsoleHighlighter : public QSyntaxHighlighter {
 public:
  explicit ConsoleHighlighter(QTextDocument* document) : QSyntaxHighlighter(document) {}

 protected:
  void highlightBlock(const QString& text) override {
    const qsizetype close = text.indexOf(QLatin1String("s] "));
    if (close < 0)
      return;
    const int tag_start = static_cast<int>(close) + 3;
    QTextCharFormat time_format;
    time_format.setForeground(QColor(120, 126, 134));
    setFormat(0, tag_start, time_format);

    const QString tag = text.mid(tag_start, kTagWidth).trimmed();
    ConsoleLevel level = ConsoleLevel::kInfo;
    for (ConsoleLevel l : {ConsoleLevel::kWarning, ConsoleLevel::kError, ConsoleLevel::kSensor}) {
      if (tag == QLatin1String(levelTag(l)))
        level = l;
    }
    QTextCharFormat tag_format;
    tag_format.setForeground(levelColour(level));
    tag_format.setFontWeight(QFont::Bold);
    setFormat(tag_start, kTagWidth, tag_format);
    if (level != ConsoleLevel::kInfo) {
      QTextCharFormat text_format;
      text_format.setForeground(levelColour(level));
      setFormat(tag_start + kTagWidth, static_cast<int>(text.size()) - tag_start - kTagWidth,
                text_format);
    }
  }
};

ConsoleWidget::ConsoleWidget(QWidget* parent) : QWidget(parent) {
  view_ = new QPlainTextEdit(this);
  view_->setObjectName(QStringLiteral("consoleView"));
  view_->setReadOnly(true);
  view_->setUndoRedoEnabled(false);
  view_->setLineWrapMode(QPlainTextEdit::NoWrap);
  view_->setMaximumBlockCount(maximum_lines_);
  view_->setFont(QFontDatabase::systemFont(QFontDatabase::FixedFont));
  view_->setTextInteractionFlags(Qt::TextSelectableByMouse | Qt::TextSelectableByKeyboard);
  highlighter_ = new ConsoleHighlighter(view_->document());

  filter_edit_ = new QLineEdit(this);
  filter_edit_->setObjectName(QStringLiteral("consoleFilter"));
  filter_edit_->setPlaceholderText(tr("Filter…"));
  filter_edit_->setClearButtonEnabled(true);
  filter_edit_->setToolTip(tr("Show only lines containing this text (case-insensitive)"));
  connect(filter_edit_, &QLineEdit::textChanged, this, &ConsoleWidget::setFilterText);

  // Two rows: filter and actions, then the level switches; one row squeezed the filter to
  // nothing in a side column of ordinary width.
  auto* bar = new QHBoxLayout;
  bar->setContentsMargins(0, 0, 0, 0);
  bar->setSpacing(6);
  bar->addWidget(filter_edit_, 1);
  auto* levels = new QHBoxLayout;
  levels->setContentsMargins(0, 0, 0, 0);
  levels->setSpacing(10);
  const std::array<QString, 4> names{tr("Info"), tr("Warnings"), tr("Errors"), tr("Sensors")};
  const std::array<QString, 4> ids{
      QStringLiteral("consoleLevelInfo"), QStringLiteral("consoleLevelWarning"),
      QStringLiteral("consoleLevelError"), QStringLiteral("consoleLevelSensor")};
  for (std::size_t i = 0; i < level_boxes_.size(); ++i) {
    auto* box = new QCheckBox(names[i], this);
    box->setObjectName(ids[i]);
    box->setChecked(true);
    box->setToolTip(tr("Show %1 lines").arg(names[i].toLower()));
    const auto level = static_cast<ConsoleLevel>(i);
    connect(box, &QCheckBox::toggled, this, [this, level](bool on) { setLevelVisible(level, on); });
    level_boxes_[i] = box;
    levels->addWidget(box);
  }
  levels->addStretch(1);

  auto* copy = new QToolButton(this);
  copy->setObjectName(QStringLiteral("consoleCopy"));
  copy->setText(tr("Copy"));
  copy->setToolTip(tr("Copy the selection, or every visible line when nothing is selected"));
  connect(copy, &QToolButton::clicked, this, &ConsoleWidget::copyToClipboard);
  auto* clear_button = new QToolButton(this);
  clear_button->setObjectName(QStringLiteral("consoleClear"));
  clear_button->setText(tr("Clear"));
  clear_button->setToolTip(tr("Remove every line"));
  connect(clear_button, &QToolButton::clicked, this, &ConsoleWidget::clear);
  pause_button_ = new QToolButton(this);
  pause_button_->setObjectName(QStringLiteral("consolePause"));
  pause_button_->setText(tr("Pause"));
  pause_button_->setCheckable(true);
  pause_button_->setToolTip(tr("Pause autoscroll (new lines are still recorded)"));
  connect(pause_button_, &QToolButton::toggled, this, &ConsoleWidget::setAutoscrollPaused);
  bar->addSpacing(6);
  bar->addWidget(copy);
  bar->addWidget(clear_button);
  bar->addWidget(pause_button_);

  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->setSpacing(4);
  layout->addLayout(bar);
  layout->addLayout(levels);
  layout->addWidget(view_, 1);

  // Lines arrive in bursts (a telemetry sample may log several); they reach the view at most
  // every 50 ms in one edit, which keeps thousands of lines per second cheap.
  flush_timer_ = new QTimer(this);
  flush_timer_->setSingleShot(true);
  flush_timer_->setInterval(50);
  connect(flush_timer_, &QTimer::timeout, this, &ConsoleWidget::flushPending);
}

ConsoleWidget::~ConsoleWidget() = default;

QString ConsoleWidget::formatLine(ConsoleLevel level, double time_s, const QString& text) {
  QString clean = text;
  for (QChar& c : clean) {
    if (c == QLatin1Char('\n') || c == QLatin1Char('\r') || c == QChar::ParagraphSeparator ||
        c == QChar::LineSeparator || c == QLatin1Char('\t'))
      c = QLatin1Char(' ');
  }
  return QStringLiteral("[%1 s] %2 %3")
      .arg(time_s, 7, 'f', 2)
      .arg(QLatin1String(levelTag(level)), -kTagWidth)
      .arg(clean);
}

void ConsoleWidget::appendEvent(ConsoleLevel level, double time_s, const QString& text) {
  lines_.push_back({level, formatLine(level, time_s, text)});
  while (lines_.size() > static_cast<std::size_t>(maximum_lines_))
    lines_.pop_front();
  if (!passes(lines_.back()))
    return;
  pending_ << lines_.back().text;
  if (pending_.size() > maximum_lines_)
    pending_.remove(0, pending_.size() - maximum_lines_);
  if (!flush_timer_->isActive())
    flush_timer_->start();
}

int ConsoleWidget::lineCount() const {
  return static_cast<int>(lines_.size());
}

bool ConsoleWidget::passes(const Line& line) const {
  if (!level_visible_[levelIndex(line.level)])
    return false;
  return filter_.isEmpty() || line.text.contains(filter_, Qt::CaseInsensitive);
}

QString ConsoleWidget::visibleText() const {
  QStringList shown;
  for (const Line& line : lines_) {
    if (passes(line))
      shown << line.text;
  }
  return shown.join(QLatin1Char('\n'));
}

void ConsoleWidget::setMaximumLines(int lines) {
  maximum_lines_ = std::max(lines, 1);
  while (lines_.size() > static_cast<std::size_t>(maximum_lines_))
    lines_.pop_front();
  view_->setMaximumBlockCount(maximum_lines_);
  rebuildView();
}

void ConsoleWidget::setFilterText(const QString& text) {
  if (text == filter_)
    return;
  filter_ = text;
  if (filter_edit_->text() != text) {
    const QSignalBlocker block(filter_edit_);
    filter_edit_->setText(text);
  }
  rebuildView();
}

void ConsoleWidget::setLevelVisible(ConsoleLevel level, bool visible) {
  const std::size_t i = levelIndex(level);
  if (level_visible_[i] == visible)
    return;
  level_visible_[i] = visible;
  {
    const QSignalBlocker block(level_boxes_[i]);
    level_boxes_[i]->setChecked(visible);
  }
  rebuildView();
}

bool ConsoleWidget::levelVisible(ConsoleLevel level) const {
  return level_visible_[levelIndex(level)];
}

void ConsoleWidget::setAutoscrollPaused(bool paused) {
  paused_ = paused;
  {
    const QSignalBlocker block(pause_button_);
    pause_button_->setChecked(paused);
  }
  if (!paused_)
    view_->verticalScrollBar()->setValue(view_->verticalScrollBar()->maximum());
}

void ConsoleWidget::clear() {
  lines_.clear();
  pending_.clear();
  view_->clear();
}

void ConsoleWidget::copyToClipboard() {
  const QString selected = view_->textCursor().selectedText();
  QString text = selected.isEmpty() ? visibleText() : selected;
  text.replace(QChar::ParagraphSeparator, QLatin1Char('\n'));
  QApplication::clipboard()->setText(text);
}

void ConsoleWidget::rebuildView() {
  pending_.clear();
  flush_timer_->stop();
  view_->setPlainText(visibleText());
  if (!paused_)
    view_->verticalScrollBar()->setValue(view_->verticalScrollBar()->maximum());
}

void ConsoleWidget::flushPending() {
  if (pending_.isEmpty())
    return;
  QScrollBar* bar = view_->verticalScrollBar();
  const int kept_position = bar->value();
  // appendPlainText starts a new block per call: one call with the lines joined.
  view_->appendPlainText(pending_.join(QLatin1Char('\n')));
  pending_.clear();
  if (paused_)
    bar->setValue(kept_position);
  else
    bar->setValue(bar->maximum());
}

}  // namespace irgs::widgets
