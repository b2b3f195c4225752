#pragma once
// The ground-station window, laid out like the thesis host UI (003_…, Fig. 3.12): the map on the
// left, command buttons top right, the console bottom right. It lays out and connects; the work
// happens in SessionController, MapFileActions and the widgets.

#include <QMainWindow>
#include <map>
#include <vector>

class QAction;
class QActionGroup;
class QSettings;
class QSplitter;
class QTabWidget;
class QTimer;

namespace irgs::widgets {
class CommandPanel;
class ConsoleWidget;
class KeyboardTeleop;
class MapCanvas;
class PlanningPanel;
}  // namespace irgs::widgets

namespace irgs::gui {

class CameraController;
class NavigationController;
class EditorController;
class ExportActions;
class LinkUi;
class LocalizationController;
class MapFileActions;
class ParametersController;
class PlanningController;
class PlotsController;
class SessionController;
class SessionStatusBar;

class MainWindow : public QMainWindow {
  Q_OBJECT

 public:
  static constexpr int kSideColumnWidth = 360;  // px, command panel and console

  // `session` and `settings` must outlive the window. Installs the keyboard teleop as an
  // application event filter (removed again in the destructor).
  MainWindow(SessionController& session, QSettings& settings, QWidget* parent = nullptr);
  ~MainWindow() override;

  widgets::MapCanvas& canvas() const { return *canvas_; }
  widgets::CommandPanel& commandPanel() const { return *panel_; }
  widgets::ConsoleWidget& console() const { return *console_; }
  widgets::KeyboardTeleop& teleop() const { return *teleop_; }
  MapFileActions& mapFiles() const { return *map_files_; }
  // The "Plan" tab beside the command panel: goal, coverage and map building.
  widgets::PlanningPanel& planningPanel() const { return *planning_panel_; }
  PlanningController& planning() const { return *planning_; }
  QTabWidget& controlTabs() const { return *control_tabs_; }
  // The robot link: mode switch, connection dialog, health panel, link state in the status bar.
  LinkUi& linkUi() const { return *link_ui_; }
  // The "Localization" menu and dock: estimator poses on the map, error plots.
  LocalizationController& localization() const { return *localization_; }
  // The map editor ("Edit" tab).
  EditorController& editor() const { return *editor_; }
  // The "Plots" dock: field browser and plot panels (View > Plots).
  PlotsController& plots() const { return *plots_; }
  // The "Parameters" dock: profile, algorithm and firmware parameters (View > Parameters).
  ParametersController& parameters() const { return *parameters_; }
  // File > Export: map view PNG/SVG, sonar grid as ROS map, session summary.
  ExportActions& exports() const { return *exports_; }
  // The ceiling camera dock (issue 7).
  CameraController& camera() const { return *camera_; }
  // Landmark navigation: the "Navigate" tab and the canvas overlay (issue 7).
  NavigationController& navigation() const { return *navigation_; }

  // Restores geometry, splitters, speeds and layers from the settings; without saved geometry
  // the window gets `default_size`.
  void restoreSettings(const QSize& default_size);
  void saveSettings();
  // Brings the status bar up to date now (it normally refreshes a few times per second).
  void refreshStatus();

 protected:
  void closeEvent(QCloseEvent* event) override;
  bool eventFilter(QObject* watched, QEvent* event) override;

 private:
  void buildLayout();
  void buildFileMenu();
  void buildViewMenu();
  void buildSimulationMenu();
  void buildHelpMenu();
  void connectSession();
  void onWorldLoaded();
  void updateTitle();
  void updateSimulationActions();
  void showShortcuts();
  void showAbout();
  // Gives the side column's tab area the height the tab needs (or the height the user last
  // dragged it to), the console the rest; `grow_only` never takes room back.
  void fitSideColumnToTab(int index, bool grow_only);

  SessionController& session_;
  QSettings& settings_;
  widgets::MapCanvas* canvas_ = nullptr;
  widgets::CommandPanel* panel_ = nullptr;
  widgets::ConsoleWidget* console_ = nullptr;
  widgets::KeyboardTeleop* teleop_ = nullptr;
  QSplitter* main_splitter_ = nullptr;
  QSplitter* side_splitter_ = nullptr;
  QTabWidget* control_tabs_ = nullptr;   // "Drive" (command panel) and "Plan"
  std::map<int, int> user_tab_heights_;  // per tab index, the height the user dragged it to, px
  widgets::PlanningPanel* planning_panel_ = nullptr;
  PlanningController* planning_ = nullptr;
  MapFileActions* map_files_ = nullptr;
  LinkUi* link_ui_ = nullptr;
  LocalizationController* localization_ = nullptr;
  EditorController* editor_ = nullptr;
  PlotsController* plots_ = nullptr;
  ParametersController* parameters_ = nullptr;
  ExportActions* exports_ = nullptr;
  CameraController* camera_ = nullptr;
  NavigationController* navigation_ = nullptr;
  SessionStatusBar* status_ = nullptr;
  QTimer* status_timer_ = nullptr;

  QAction* follow_action_ = nullptr;
  std::vector<QAction*> layer_actions_;
  QAction* run_pause_action_ = nullptr;
  QAction* step_action_ = nullptr;
  QAction* reset_robot_action_ = nullptr;
  QActionGroup* speed_group_ = nullptr;
};

}  // namespace irgs::gui
