#pragma once
// The plots dock's contents: the field browser (with a filter box) beside a column of plot
// panels, and a toolbar — add/remove panel, pause/resume all, time window, export the current
// panel as CSV or PNG. Double-clicked fields go to the current panel (the one last clicked or
// dropped on, outlined); panels repaint on one timer (kRefreshInterval_ms) whatever the data
// rate.

#include <QString>
#include <QWidget>
#include <vector>

class QComboBox;
class QLineEdit;
class QSplitter;
class QTimer;
class QToolButton;

namespace irgs::widgets {

class FieldBrowser;
class PlotDataHub;
class PlotPanel;

class PlotsDock : public QWidget {
  Q_OBJECT

 public:
  static constexpr int kRefreshInterval_ms = 50;  // 20 frames/s
  static constexpr int kMaxPanels = 8;

  explicit PlotsDock(PlotDataHub& hub, QWidget* parent = nullptr);
  ~PlotsDock() override;

  FieldBrowser& browser() const { return *browser_; }
  PlotDataHub& hub() const { return hub_; }
  int panelCount() const { return static_cast<int>(panels_.size()); }
  PlotPanel& panel(int index) const { return *panels_.at(static_cast<std::size_t>(index)); }
  PlotPanel* currentPanel() const { return current_; }

  // Adds a panel below the others (null beyond kMaxPanels) and makes it current.
  PlotPanel* addPanel();
  // Removes the current panel (the last one stays).
  void removeCurrentPanel();
  void setCurrentPanel(PlotPanel* panel);
  // Adds `keys` to the current panel.
  void plotFields(const QStringList& keys);
  // Pauses / resumes every panel.
  void setAllPaused(bool paused);
  // The time window of every panel (seconds).
  void setWindow_s(double window_s);

  // Repaints the panels whose data changed (also on the timer).
  void refreshNow();

 private:
  void exportCurrent(bool png);

  PlotDataHub& hub_;
  FieldBrowser* browser_ = nullptr;
  QLineEdit* filter_ = nullptr;
  QSplitter* panel_column_ = nullptr;
  QComboBox* window_choice_ = nullptr;
  QToolButton* pause_button_ = nullptr;
  QTimer* refresh_ = nullptr;
  std::vector<PlotPanel*> panels_;
  PlotPanel* current_ = nullptr;
};

}  // namespace irgs::widgets
