#pragma once
// One plot panel of the plots dock: traces of PlotDataHub fields against time, drawn with
// QPainter from the series' min/max decimation (one column per pixel, so a 10-minute window of
// 50 Hz data costs the same to draw as a 10-second one). Qt Charts redraws every point of
// every series; see docs/decisions.md ("Plots dock").
//
// Fields arrive by drag and drop (the field browser's kFieldMimeType) or addField(). Each trace
// has a display scale (a factor and a unit label, e.g. rad -> deg) and the legend shows its
// newest value and its min/max over the visible window. The time window follows the newest data
// (live) until paused; the mouse wheel zooms the time axis, dragging pans (and pauses), a
// double-click returns to live. The y axis fits the visible data unless fixed by setYRange().

#include <QColor>
#include <QString>
#include <QStringList>
#include <QWidget>
#include <optional>
#include <vector>

#include "widgets/plots/plot_series.hpp"

namespace irgs::widgets {

class PlotDataHub;

// The MIME type of dragged plot fields: the keys, one per line (UTF-8).
inline constexpr const char* kFieldMimeType = "application/x-irgs-plot-fields";

struct PlotTrace {
  QString key;
  QColor colour;
  double scale = 1.0;    // displayed = value * scale
  QString display_unit;  // the unit after scaling
};

// How a unit is shown by default: radians as degrees, everything else as it is.
PlotTrace defaultTrace(const QString& key, const QString& unit, const QColor& colour);

class PlotPanel : public QWidget {
  Q_OBJECT

 public:
  static constexpr double kDefaultWindow_s = 30.0;
  static constexpr double kMinWindow_s = 0.5;
  static constexpr double kMaxWindow_s = 24.0 * 3600.0;

  explicit PlotPanel(PlotDataHub& hub, QWidget* parent = nullptr);
  ~PlotPanel() override;

  // Adds a trace for `key` (false when the hub has no such field or it is shown already).
  bool addField(const QString& key);
  bool removeField(const QString& key);
  void clearFields();
  const std::vector<PlotTrace>& traces() const { return traces_; }
  // Sets a trace's display scale and unit (false for an unknown key or a non-finite factor).
  bool setTraceScale(const QString& key, double scale, const QString& display_unit);

  // Time window length and where it ends.
  void setWindow_s(double window_s);
  double window_s() const { return window_s_; }
  void setPaused(bool paused);
  bool paused() const { return paused_; }
  // The visible time interval: [end - window, end]; end is the hub's newest time while live.
  std::pair<double, double> visibleTime() const;
  // Fixes the y axis (nullopt: fit the visible data).
  void setYRange(std::optional<PlotRange> range);
  // The y interval drawn, in display units (fitted or fixed).
  PlotRange visibleY() const;

  // Min/max of a trace over the visible window, in display units; nullopt without samples.
  std::optional<PlotRange> visibleRange(const QString& key) const;

  // The visible window of every trace as CSV: time_s, then one column per trace in display
  // units (header "key [unit]"); rows are the union of the traces' sample times, a blank cell
  // where a trace has no sample at that time. Returns an error message or empty.
  QString exportCsv(const QString& path) const;
  // Renders the panel to a PNG of `size` (the widget's size when empty).
  QString exportPng(const QString& path, QSize size = {}) const;

  // Highlights the panel as the one double-clicked fields go to.
  void setCurrent(bool current);
  bool isCurrent() const { return current_; }

  // Repaints when the hub has new data or the view changed (the dock calls it on a timer).
  void refresh();

  QSize minimumSizeHint() const override { return {240, 140}; }

 signals:
  void activated(irgs::widgets::PlotPanel* panel);  // clicked or received a drop
  void tracesChanged();
  void pausedChanged(bool paused);

 protected:
  void paintEvent(QPaintEvent* event) override;
  void dragEnterEvent(QDragEnterEvent* event) override;
  void dragMoveEvent(QDragMoveEvent* event) override;
  void dropEvent(QDropEvent* event) override;
  void wheelEvent(QWheelEvent* event) override;
  void mousePressEvent(QMouseEvent* event) override;
  void mouseMoveEvent(QMouseEvent* event) override;
  void mouseReleaseEvent(QMouseEvent* event) override;
  void mouseDoubleClickEvent(QMouseEvent* event) override;
  void contextMenuEvent(QContextMenuEvent* event) override;

 private:
  QRect plotRect() const;
  void paintTo(QPainter& painter, const QRect& area) const;
  void askScale(const QString& key);
  void chooseCsv();
  void choosePng();

  PlotDataHub& hub_;
  std::vector<PlotTrace> traces_;
  double window_s_ = kDefaultWindow_s;
  bool paused_ = false;
  double paused_end_s_ = 0.0;
  std::optional<PlotRange> fixed_y_;
  bool current_ = false;
  std::uint64_t drawn_revision_ = 0;
  bool dirty_ = true;
  std::optional<QPoint> drag_from_;
  double drag_end_s_ = 0.0;
  int next_colour_ = 0;
};

}  // namespace irgs::widgets
