#pragma once
// The localization plots (Qt Charts): position and heading error of an estimator against truth
// over time with the filter's own 3-sigma bounds, the dead-reckoning position error for
// comparison, and the covariance terms (the 1-sigma of x, y, theta and the x-y correlation) —
// the papers' Fig. 12/14/15. Points are appended live; the charts are redrawn at most every
// kRefreshInterval_ms. Exports the collected series as CSV and the visible chart as PNG.
//
// Units on screen: metres, degrees, seconds. Input in SI (radians).

#include <QString>
#include <QWidget>
#include <vector>

class QTabWidget;
class QTimer;
class QLabel;
class QChart;
class QChartView;
class QLineSeries;
class QValueAxis;

namespace irgs::widgets {

// One sample of the plots: error = estimate - truth (world frame), sigmas = sqrt(diag P).
struct ErrorPlotPoint {
  double time_s = 0.0;
  double error_x_m = 0.0;
  double error_y_m = 0.0;
  double error_theta_rad = 0.0;
  double sigma_x_m = 0.0;
  double sigma_y_m = 0.0;
  double sigma_theta_rad = 0.0;
  double correlation_xy = 0.0;  // P_xy / (sigma_x sigma_y), in [-1, 1]
  double dr_position_error_m = 0.0;
  double nees = -1.0;  // -1 when undefined
};

class ErrorPlotPanel : public QWidget {
  Q_OBJECT

 public:
  static constexpr int kRefreshInterval_ms = 200;
  // Points kept; beyond, every second point of the older half is dropped (the plot keeps the
  // whole run at a coarser resolution).
  static constexpr std::size_t kMaxPoints = 6000;
  // A point closer in time than this to the previous one is not stored (live feeds at 100 Hz).
  static constexpr double kMinSpacing_s = 0.05;

  explicit ErrorPlotPanel(QWidget* parent = nullptr);
  ~ErrorPlotPanel() override;

  // Title line above the charts, e.g. the estimator's name.
  void setEstimatorName(const QString& name);
  // Appends a point; non-finite values and times earlier than the last point are ignored
  // (returns false). A time earlier than the last by more than a second starts a new run
  // (clear()) — the simulation was reset.
  bool addPoint(const ErrorPlotPoint& point);
  void clear();
  const std::vector<ErrorPlotPoint>& points() const { return points_; }

  // Redraws now (tests, screenshots) instead of waiting for the refresh timer.
  void refreshNow();

  // Writes the points as CSV (metres, degrees, seconds). Returns an error message or empty.
  QString exportCsv(const QString& path) const;
  // Renders the current tab's chart to a PNG of `size` (the widget's size when empty).
  QString exportPng(const QString& path, QSize size = {}) const;

  int currentChart() const;
  void setCurrentChart(int index);  // 0 position, 1 heading, 2 covariance

 signals:
  void exportRequested();  // the user asked for an export from the panel's buttons (informs)

 private:
  void scheduleRefresh();
  void onExportCsv();
  void onExportPng();

  QLabel* title_ = nullptr;
  QLabel* stats_ = nullptr;
  QTabWidget* tabs_ = nullptr;
  QTimer* refresh_ = nullptr;
  struct Chart;
  std::vector<Chart*> charts_;
  std::vector<ErrorPlotPoint> points_;
};

}  // namespace irgs::widgets
