#pragma once
// Localization in the GUI (issue 5, item 6): runs the chosen estimator (EstimatorRunner) on the
// session's simulator telemetry and shows it — estimator and dead-reckoning poses with their
// 2-sigma ellipses and heading wedges and the matched walls/corners on the map canvas, the error
// plots (ErrorPlotPanel) in a dock — with a "Localization" menu: the estimator per run, the
// initial pose set by dragging on the map (press at the position, drag towards the heading,
// release), and pause + single update with the innovation, gate value and matched feature of
// each reading printed to the console.
//
// Needs ground truth (simulator mode): a linked robot's samples have none, so echoes cannot be
// simulated; the controller then says so and shows dead reckoning only.

#include <QObject>
#include <QPointer>
#include <QString>
#include <functional>
#include <memory>
#include <optional>

#include "core/estimation/estimator_runner.hpp"
#include "core/robot/telemetry.hpp"

class QAction;
class QActionGroup;
class QComboBox;
class QDockWidget;
class QLabel;
class QMainWindow;
class QMenu;
class QPushButton;

namespace irgs::widgets {
class ErrorPlotPanel;
class MapCanvas;
}  // namespace irgs::widgets

namespace irgs::gui {

class SessionController;

class LocalizationController : public QObject {
  Q_OBJECT

 public:
  // Maximum robot steps one "Step Update" advances while looking for the next stereo reading.
  static constexpr int kMaxStepsPerUpdate = 100;

  // Adds the dock (hidden until an estimator runs) and the "Localization" menu to `window`
  // (inserted before `before_menu` when given). Everything must outlive the controller.
  LocalizationController(SessionController& session, widgets::MapCanvas& canvas,
                         QMainWindow& window, QAction* before_menu = nullptr);
  ~LocalizationController() override;

  // Starts `kind` at the current initial pose (the map's start, or the one dragged out); nullopt
  // switches localization off. Restarts the plots.
  void setEstimator(std::optional<EstimatorKind> kind);
  std::optional<EstimatorKind> estimator() const;
  // Sets the estimator's initial belief (the robot itself stays where it is) and restarts.
  void setInitialPose(const Pose2& pose);
  std::optional<Pose2> initialPose() const { return initial_pose_; }
  // Arms the canvas for dragging out the initial pose (one drag, then disarms).
  void armInitialPoseDrag(bool armed);
  bool initialPoseDragArmed() const { return drag_armed_; }
  // Pauses the simulation and advances it until the estimator has processed one update (a
  // stereo firing for the EKF, one sample otherwise); prints the update to the console.
  void stepUpdate();

  const EstimatorRunner* runner() const { return runner_.get(); }
  // Adjusts every estimator's configuration after the controller's defaults (the parameters
  // panel: EKF gates, noise); restarts a running estimator so it takes effect. Empty: none.
  using ConfigAdjuster = std::function<void(EstimatorRunnerConfig& config)>;
  void setConfigAdjuster(ConfigAdjuster adjust);
  widgets::ErrorPlotPanel& plots() const { return *plots_; }
  QDockWidget& dock() const { return *dock_; }
  QMenu& menu() const { return *menu_; }

 protected:
  bool eventFilter(QObject* watched, QEvent* event) override;

 private:
  void onSample(const TelemetrySample& sample);
  void restart();
  void updateOverlay();
  void printStep(const EstimatorStep& step);
  void syncUi();

  SessionController& session_;
  widgets::MapCanvas& canvas_;
  QPointer<widgets::MapCanvas> canvas_alive_;  // the canvas may die first (window teardown)
  QMainWindow& window_;
  QDockWidget* dock_ = nullptr;
  widgets::ErrorPlotPanel* plots_ = nullptr;
  QComboBox* choice_ = nullptr;
  QLabel* state_ = nullptr;
  QPushButton* drag_button_ = nullptr;
  QMenu* menu_ = nullptr;
  QActionGroup* kind_group_ = nullptr;
  QAction* drag_action_ = nullptr;

  std::unique_ptr<EstimatorRunner> runner_;
  std::optional<EstimatorKind> kind_;
  ConfigAdjuster adjust_;
  std::optional<Pose2> initial_pose_;
  EstimatorStep last_with_readings_;  // the matches shown until the next firing
  bool warned_no_truth_ = false;
  bool warned_no_gyro_ = false;
  bool warned_no_mouse_ = false;
  bool warned_no_casters_ = false;
  bool stepping_ = false;
  bool drag_armed_ = false;
  std::optional<Vec2> drag_from_;
};

}  // namespace irgs::gui
