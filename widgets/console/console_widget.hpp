#pragma once
// The event console: timestamped, level-coloured lines with a substring filter, level toggles,
// copy, clear and a pause-autoscroll switch. Lines are kept (bounded) so filters can be changed
// after the fact; the view shows the lines that pass the filter.

#include <QString>
#include <QWidget>
#include <array>
#include <deque>

class QCheckBox;
class QLineEdit;
class QPlainTextEdit;
class QTimer;
class QToolButton;

namespace irgs::widgets {

enum class ConsoleLevel { kInfo, kWarning, kError, kSensor };

class ConsoleHighlighter;

class ConsoleWidget : public QWidget {
  Q_OBJECT

 public:
  static constexpr int kDefaultMaximumLines = 20000;

  explicit ConsoleWidget(QWidget* parent = nullptr);
  ~ConsoleWidget() override;

  // Appends one event. Line breaks in `text` are folded to spaces (one event = one line).
  void appendEvent(ConsoleLevel level, double time_s, const QString& text);
  // Number of lines held (all levels, before filtering; at most maximumLines()).
  int lineCount() const;
  // The lines that pass the filter, joined by '\n' (what the view shows; used by copy and tests).
  QString visibleText() const;

  void setMaximumLines(int lines);  // >= 1; drops the oldest lines beyond it
  int maximumLines() const { return maximum_lines_; }
  void setFilterText(const QString& text);  // case-insensitive substring
  void setLevelVisible(ConsoleLevel level, bool visible);
  bool levelVisible(ConsoleLevel level) const;
  void setAutoscrollPaused(bool paused);
  bool autoscrollPaused() const { return paused_; }

  // Formats one line exactly as shown: "[  12.34 s] WARN   text".
  static QString formatLine(ConsoleLevel level, double time_s, const QString& text);

 public slots:
  void clear();
  void copyToClipboard();  // the selection, or every visible line when nothing is selected

 private:
  struct Line {
    ConsoleLevel level;
    QString text;  // formatted
  };

  bool passes(const Line& line) const;
  void rebuildView();
  void flushPending();

  std::deque<Line> lines_;
  QStringList pending_;  // visible lines not yet in the view (flushed on a short timer)
  int maximum_lines_ = kDefaultMaximumLines;
  QString filter_;
  std::array<bool, 4> level_visible_{true, true, true, true};
  bool paused_ = false;

  QPlainTextEdit* view_ = nullptr;
  ConsoleHighlighter* highlighter_ = nullptr;
  QLineEdit* filter_edit_ = nullptr;
  std::array<QCheckBox*, 4> level_boxes_{};
  QToolButton* pause_button_ = nullptr;
  QTimer* flush_timer_ = nullptr;
};

}  // namespace irgs::widgets
