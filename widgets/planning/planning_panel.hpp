#pragma once
// The planning and behaviour panel: what to plan on, and three tabs — click-to-goal (raw A*
// against the amended path: turns, length, turn-aware time; drive), coverage over a dragged
// region (spiral or boustrophedon, lane width, live coverage %), and map building (start,
// pause, abort, phase and progress, save the built map).
//
// Like CommandPanel: setters never emit signals; signals come from user actions only. The panel
// holds no planner: the app plans and pushes the numbers back through the setters.

#include <QString>
#include <QWidget>
#include <optional>

#include "core/planning/coverage.hpp"

class QCheckBox;
class QComboBox;
class QDoubleSpinBox;
class QLabel;
class QProgressBar;
class QPushButton;
class QTabWidget;

namespace irgs::widgets {

enum class PlanSource { kWorldMap, kSonarGrid, kBuiltMap };

class PlanningPanel : public QWidget {
  Q_OBJECT

 public:
  enum class Tab { kGoal, kCoverage, kMapBuilding };
  // What a running behaviour belongs to (which tab's Stop/Drive buttons are live).
  enum class Task { kNone, kGoal, kCoverage, kMapBuilding };

  struct PathStats {
    int turns = 0;
    double length_m = 0.0;
    double time_s = 0.0;
  };

  explicit PlanningPanel(QWidget* parent = nullptr);

  PlanSource planSource() const;
  void setPlanSource(PlanSource source);
  // Enables a source in the combo (the built map exists only after map building).
  void setPlanSourceAvailable(PlanSource source, bool available);

  Tab currentTab() const;
  void setCurrentTab(Tab tab);

  // Goal tab. Without stats the table shows dashes; `note` goes below it (errors, budget).
  void setGoalPreview(const std::optional<PathStats>& raw, const std::optional<PathStats>& amended,
                      const QString& note);
  void setPickGoalChecked(bool checked);
  bool pickGoalChecked() const;

  // Coverage tab.
  irgs::CoveragePattern coveragePattern() const;
  double laneWidth() const;  // m
  void setLaneWidth(double lane_m);
  void setSelectRegionChecked(bool checked);
  bool selectRegionChecked() const;
  void setCoverageSummary(const QString& text);
  void setCoverage(std::optional<double> fraction);  // live coverage of the region, 0..1

  // Map-building tab.
  void setMapBuildStatus(const QString& phase, double progress);
  void setBuiltMapAvailable(bool available);
  void setMapBuildingAvailable(bool available, const QString& why_not);

  // Which task runs (buttons follow) and whether it is paused.
  void setRunningTask(Task task, bool paused = false);
  Task runningTask() const { return running_; }
  // Whether there is a goal or coverage path to drive.
  void setGoalDrivable(bool drivable);
  void setCoverageDrivable(bool drivable);

 signals:
  void planSourceChanged(irgs::widgets::PlanSource source);
  void currentTabChanged(irgs::widgets::PlanningPanel::Tab tab);
  void pickGoalToggled(bool checked);
  void driveGoalRequested();
  void selectRegionToggled(bool checked);
  void coverageSettingsChanged();  // pattern or lane width
  void driveCoverageRequested();
  void stopRequested();
  void mapBuildStartRequested();
  void mapBuildPauseToggled(bool paused);
  void mapBuildAbortRequested();
  void saveBuiltMapRequested();

 private:
  QWidget* buildGoalTab();
  QWidget* buildCoverageTab();
  QWidget* buildMapBuildingTab();
  void updateButtons();

  QComboBox* source_combo_ = nullptr;
  QTabWidget* tabs_ = nullptr;

  QPushButton* pick_goal_ = nullptr;
  QPushButton* drive_goal_ = nullptr;
  QPushButton* stop_goal_ = nullptr;
  QLabel* raw_turns_ = nullptr;
  QLabel* raw_length_ = nullptr;
  QLabel* raw_time_ = nullptr;
  QLabel* amended_turns_ = nullptr;
  QLabel* amended_length_ = nullptr;
  QLabel* amended_time_ = nullptr;
  QLabel* goal_note_ = nullptr;

  QPushButton* select_region_ = nullptr;
  QComboBox* pattern_combo_ = nullptr;
  QDoubleSpinBox* lane_spin_ = nullptr;
  QPushButton* drive_coverage_ = nullptr;
  QPushButton* stop_coverage_ = nullptr;
  QLabel* coverage_summary_ = nullptr;
  QProgressBar* coverage_bar_ = nullptr;

  QPushButton* build_start_ = nullptr;
  QPushButton* build_pause_ = nullptr;
  QPushButton* build_abort_ = nullptr;
  QPushButton* build_save_ = nullptr;
  QLabel* build_phase_ = nullptr;
  QProgressBar* build_bar_ = nullptr;

  Task running_ = Task::kNone;
  bool paused_ = false;
  bool goal_drivable_ = false;
  bool coverage_drivable_ = false;
  bool built_map_ = false;
  bool map_building_available_ = true;
};

}  // namespace irgs::widgets
