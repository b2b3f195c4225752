#include "app/gui/main_window.hpp"

#include <QAction>
#include <QActionGroup>
#include <QApplication>
#include <QCloseEvent>
#include <QFileInfo>
#include <QMenu>
#include <QMenuBar>
#include <QMessageBox>
#include <QSettings>
#include <QSplitter>
#include <QStackedWidget>
#include <QStatusBar>
#include <QTabBar>
#include <QTabWidget>
#include <QTimer>
#include <algorithm>
#include <array>

#include "app/gui/app_settings.hpp"
#include "app/gui/camera_controller.hpp"
#include "app/gui/editor_controller.hpp"
#include "app/gui/export_actions.hpp"
#include "app/gui/link_ui.hpp"
#include "app/gui/localization_controller.hpp"
#include "app/gui/map_file_actions.hpp"
#include "app/gui/navigation_controller.hpp"
#include "app/gui/parameters_controller.hpp"
#include "app/gui/planning_controller.hpp"
#include "app/gui/plots_controller.hpp"
#include "app/gui/session_controller.hpp"
#include "app/gui/session_status_bar.hpp"
#include "app/gui/shortcuts.hpp"
#include "widgets/canvas/map_canvas.hpp"
#include "widgets/command/command_panel.hpp"
#include "widgets/console/console_widget.hpp"
#include "widgets/link/link_health_panel.hpp"
#include "widgets/planning/planning_panel.hpp"
#include "widgets/teleop/keyboard_teleop.hpp"

namespace irgs::gui {
namespace {

using widgets::MapCanvas;

struct LayerInfo {
  MapCanvas::Layer layer;
  const char* key;    // settings key under view/layers
  const char* label;  // menu text
};

constexpr std::array<LayerInfo, 9> kLayers{{
    {MapCanvas::Layer::kGrid, "grid", "Occupancy &Grid (Sonar Map)"},
    {MapCanvas::Layer::kRaster, "raster", "&Raster Map"},
    {MapCanvas::Layer::kWalls, "walls", "&Walls and Obstacles"},
    {MapCanvas::Layer::kFeatures, "features", "Corners and &Edges"},
    {MapCanvas::Layer::kCeiling, "ceiling", "&Ceiling Markers and Lights"},
    {MapCanvas::Layer::kGraph, "graph", "&Topological Graph"},
    {MapCanvas::Layer::kSonar, "sonar", "&Sonar Cones"},
    {MapCanvas::Layer::kTrail, "trail", "Tr&ail"},
    {MapCanvas::Layer::kTruth, "truth", "True &Pose (Simulator)"},
}};

struct SpeedChoice {
  double factor;
  const char* label;
  const QKeySequence* keys;
};

const std::array<SpeedChoice, 4> kSpeeds{{
    {1.0, "Speed &1×", &shortcuts::kSpeed1},
    {2.0, "Speed &2×", &shortcuts::kSpeed2},
    {10.0, "Speed 1&0×", &shortcuts::kSpeed10},
    {0.0, "Speed &Max", &shortcuts::kSpeedMax},
}};

widgets::ConsoleLevel toConsoleLevel(EventLevel level) {
  switch (level) {
    case EventLevel::kInfo:
      return widgets::ConsoleLevel::kInfo;
    case EventLevel::kWarning:
      return widgets::ConsoleLevel::kWarning;
    case EventLevel::kError:
      return widgets::ConsoleLevel::kError;
    case EventLevel::kSensor:
      return widgets::ConsoleLevel::kSensor;
  }
  return widgets::ConsoleLevel::kInfo;
}

QString settingsKey(const char* key) {
  return QString::fromLatin1(key);
}

}  // namespace

MainWindow::MainWindow(SessionController& session, QSettings& settings, QWidget* parent)
    : QMainWindow(parent), session_(session), settings_(settings) {
  buildLayout();
  map_files_ = new MapFileActions(session_, settings_, *this);
  buildFileMenu();
  buildViewMenu();
  buildSimulationMenu();
  localization_ = new LocalizationController(session_, *canvas_, *this);
  camera_ = new CameraController(session_, *this);  // the "Camera" dock (View menu)
  navigation_ = new NavigationController(session_, *canvas_, *control_tabs_, this);  // "Navigate"
  // The map editor: the "Edit" tab, the tool layer on the canvas, autosave and recovery.
  editor_ = new EditorController(session_, *map_files_, *canvas_, *control_tabs_, *this);
  QTimer::singleShot(0, editor_, [this] { editor_->offerRecovery(); });
  buildHelpMenu();
  status_ = new SessionStatusBar(*statusBar(), this);
  // The link-health panel sits under the command panel (shown while a robot is linked).
  link_ui_ = new LinkUi(session_, settings_, *panel_, *statusBar(), *this);
  side_splitter_->insertWidget(1, &link_ui_->healthPanel());
  side_splitter_->setStretchFactor(1, 0);
  side_splitter_->setStretchFactor(2, 1);
  // Each tab gets the height it needs in the side column (or the one the user dragged it to).
  connect(control_tabs_, &QTabWidget::currentChanged, this,
          [this](int index) { fitSideColumnToTab(index, false); });
  if (auto* stack = control_tabs_->findChild<QStackedWidget*>())
    stack->installEventFilter(this);
  connect(side_splitter_, &QSplitter::splitterMoved, this, [this] {
    user_tab_heights_[control_tabs_->currentIndex()] = side_splitter_->sizes().value(0);
  });
  plots_ = new PlotsController(session_, *localization_, link_ui_->controller(), *this);
  exports_ = new ExportActions(session_, *canvas_, link_ui_->controller(), *this);
  parameters_ = new ParametersController(session_, *localization_, *planning_,
                                         link_ui_->controller(), settings_, *this);
  connectSession();

  teleop_ = new widgets::KeyboardTeleop(this);
  teleop_->setSpeeds(panel_->linearSpeed(), panel_->angularSpeed());
  qApp->installEventFilter(teleop_);
  connect(teleop_, &widgets::KeyboardTeleop::commandChanged, &session_, &SessionController::drive);
  connect(teleop_, &widgets::KeyboardTeleop::stopPressed, &session_, &SessionController::stopRobot);
  // STOP ends whatever drives the robot (a behaviour, a delivery, a square, a drive script).
  connect(teleop_, &widgets::KeyboardTeleop::stopPressed, this,
          [this] { session_.runner().stop(tr("STOP pressed")); });

  status_timer_ = new QTimer(this);
  status_timer_->setInterval(250);
  connect(status_timer_, &QTimer::timeout, this, [this] { status_->refresh(session_); });
  status_timer_->start();

  if (session_.robot() != nullptr)
    onWorldLoaded();
  updateSimulationActions();
  status_->refresh(session_);
}

MainWindow::~MainWindow() {
  qApp->removeEventFilter(teleop_);
}

void MainWindow::buildLayout() {
  canvas_ = new MapCanvas(this);
  canvas_->setRobotProfile(session_.profile());
  canvas_->setGrid(&session_.grid());
  panel_ = new widgets::CommandPanel(this);
  panel_->setMode(widgets::RobotMode::kSimulator);
  console_ = new widgets::ConsoleWidget(this);

  side_splitter_ = new QSplitter(Qt::Vertical, this);
  side_splitter_->setObjectName(QStringLiteral("sideSplitter"));
  // The command panel and the planning panel share the top of the side column as tabs.
  planning_panel_ = new widgets::PlanningPanel(this);
  planning_ = new PlanningController(session_, *canvas_, *planning_panel_, this);
  control_tabs_ = new QTabWidget(this);
  control_tabs_->setObjectName(QStringLiteral("controlTabs"));
  control_tabs_->setDocumentMode(true);
  control_tabs_->addTab(panel_, tr("Drive"));
  control_tabs_->addTab(planning_panel_, tr("Plan"));
  side_splitter_->addWidget(control_tabs_);
  side_splitter_->addWidget(console_);
  side_splitter_->setStretchFactor(0, 0);
  side_splitter_->setStretchFactor(1, 1);
  side_splitter_->setChildrenCollapsible(false);

  main_splitter_ = new QSplitter(Qt::Horizontal, this);
  main_splitter_->setObjectName(QStringLiteral("mainSplitter"));
  main_splitter_->addWidget(canvas_);
  main_splitter_->addWidget(side_splitter_);
  main_splitter_->setStretchFactor(0, 1);
  main_splitter_->setStretchFactor(1, 0);
  main_splitter_->setChildrenCollapsible(false);
  setCentralWidget(main_splitter_);
}

void MainWindow::buildFileMenu() {
  QMenu* menu = menuBar()->addMenu(tr("&File"));
  menu->setObjectName(QStringLiteral("fileMenu"));  // ExportActions adds its submenu
  menu->addAction(map_files_->openAction());
  menu->addMenu(map_files_->recentMenu());
  menu->addSeparator();
  menu->addAction(map_files_->saveAction());
  menu->addAction(map_files_->saveAsAction());
  menu->addSeparator();
  QAction* quit = menu->addAction(tr("&Quit"), this, &QWidget::close);
  quit->setShortcut(QKeySequence::Quit);
  quit->setMenuRole(QAction::QuitRole);
  connect(map_files_, &MapFileActions::currentFileChanged, this, &MainWindow::updateTitle);
}

void MainWindow::buildViewMenu() {
  QMenu* menu = menuBar()->addMenu(tr("&View"));
  menu->setObjectName(QStringLiteral("viewMenu"));  // PlotsController adds its toggle
  QAction* fit = menu->addAction(tr("&Zoom to Fit"), canvas_, &MapCanvas::zoomToFit);
  fit->setShortcut(shortcuts::kZoomToFit);

  follow_action_ = menu->addAction(tr("&Follow Robot"));
  follow_action_->setCheckable(true);
  follow_action_->setShortcut(shortcuts::kFollowRobot);
  connect(follow_action_, &QAction::toggled, canvas_, &MapCanvas::setFollowRobot);
  connect(canvas_, &MapCanvas::followRobotChanged, follow_action_, &QAction::setChecked);

  QMenu* layers = menu->addMenu(tr("&Layers"));
  for (const LayerInfo& info : kLayers) {
    QAction* action = layers->addAction(tr(info.label));
    action->setCheckable(true);
    action->setChecked(true);
    const MapCanvas::Layer layer = info.layer;
    connect(action, &QAction::toggled, canvas_,
            [this, layer](bool visible) { canvas_->setLayerVisible(layer, visible); });
    layer_actions_.push_back(action);
  }

  menu->addSeparator();
  QAction* clear_trail = menu->addAction(tr("Clear &Trail"), canvas_, &MapCanvas::clearTrail);
  clear_trail->setShortcut(shortcuts::kClearTrail);
  QAction* reset_grid = menu->addAction(tr("Reset &Grid"), this, [this] {
    session_.resetGrid();
    session_.report(EventLevel::kInfo, tr("Occupancy grid cleared"));
  });
  reset_grid->setShortcut(shortcuts::kResetGrid);
}

void MainWindow::buildSimulationMenu() {
  QMenu* menu = menuBar()->addMenu(tr("&Simulation"));
  run_pause_action_ = menu->addAction(tr("&Pause"));
  run_pause_action_->setShortcut(shortcuts::kRunPause);
  connect(run_pause_action_, &QAction::triggered, this,
          [this] { session_.setPaused(!session_.paused()); });
  step_action_ = menu->addAction(tr("&Step"), &session_, &SessionController::singleStep);
  step_action_->setShortcut(shortcuts::kStep);

  menu->addSeparator();
  speed_group_ = new QActionGroup(this);
  for (const SpeedChoice& choice : kSpeeds) {
    QAction* action = menu->addAction(tr(choice.label));
    action->setCheckable(true);
    action->setShortcut(*choice.keys);
    action->setData(choice.factor);
    speed_group_->addAction(action);
    const double factor = choice.factor;
    connect(action, &QAction::triggered, &session_,
            [this, factor] { session_.setSpeedFactor(factor); });
  }

  menu->addSeparator();
  reset_robot_action_ = menu->addAction(tr("&Reset Robot to Start Pose"), &session_,
                                        &SessionController::resetRobotToStart);
  reset_robot_action_->setShortcut(shortcuts::kResetRobot);
}

void MainWindow::buildHelpMenu() {
  QMenu* menu = menuBar()->addMenu(tr("&Help"));
  QAction* keys = menu->addAction(tr("&Keyboard Shortcuts"), this, &MainWindow::showShortcuts);
  keys->setShortcut(shortcuts::kHelp);
  QAction* about = menu->addAction(tr("&About IRGS"), this, &MainWindow::showAbout);
  about->setMenuRole(QAction::AboutRole);
}

void MainWindow::connectSession() {
  connect(&session_, &SessionController::consoleEvent, console_,
          [this](EventLevel level, double time_s, const QString& text) {
            console_->appendEvent(toConsoleLevel(level), time_s, text);
          });
  connect(&session_, &SessionController::worldLoaded, this, &MainWindow::onWorldLoaded);
  connect(&session_, &SessionController::robotReplaced, canvas_, &MapCanvas::clearTrail);
  connect(&session_, &SessionController::robotStateChanged, canvas_, &MapCanvas::setRobotState);
  connect(&session_, &SessionController::gridChanged, canvas_,
          [this](const OccupancyGrid::CellRect& dirty) { canvas_->gridUpdated(dirty); });
  connect(&session_, &SessionController::gridReset, canvas_,
          [this] { canvas_->setGrid(&session_.grid()); });
  connect(&session_, &SessionController::pausedChanged, this, &MainWindow::updateSimulationActions);
  connect(&session_, &SessionController::speedFactorChanged, this,
          &MainWindow::updateSimulationActions);

  connect(panel_, &widgets::CommandPanel::driveRequested, &session_, &SessionController::drive);
  connect(panel_, &widgets::CommandPanel::stopRequested, &session_, &SessionController::stopRobot);
  connect(panel_, &widgets::CommandPanel::stopRequested, this,
          [this] { session_.runner().stop(tr("STOP pressed")); });
  connect(panel_, &widgets::CommandPanel::pausedChanged, &session_, &SessionController::setPaused);
  connect(panel_, &widgets::CommandPanel::stepRequested, &session_, &SessionController::singleStep);
  connect(panel_, &widgets::CommandPanel::simSpeedChanged, &session_,
          &SessionController::setSpeedFactor);
  connect(panel_, &widgets::CommandPanel::driveSpeedsChanged, this,
          [this](double linear_mps, double angular_radps) {
            teleop_->setSpeeds(linear_mps, angular_radps);
          });
  // Simulator <-> robot link: LinkUi handles the mode switch; simulation-only actions follow
  // the robot the session has.
  connect(&session_, &SessionController::robotReplaced, this, &MainWindow::updateSimulationActions);

  connect(canvas_, &MapCanvas::cursorMoved, status_, &SessionStatusBar::setCursor);
  connect(&session_, &SessionController::ticked, status_,
          [this] { status_->refreshTime(session_); });
}

void MainWindow::onWorldLoaded() {
  canvas_->setWorldMap(session_.worldMap());
  canvas_->setGrid(&session_.grid());
  canvas_->clearTrail();
  if (session_.latestSample())
    canvas_->setRobotState(*session_.latestSample());
  canvas_->zoomToFit();
  updateTitle();
  updateSimulationActions();
}

void MainWindow::updateTitle() {
  const QString name = QString::fromStdString(session_.worldMap().name);
  const QString file =
      map_files_->currentFile().isEmpty() ? session_.worldSource() : map_files_->currentFile();
  QString title = QStringLiteral("IRGS");
  if (!name.isEmpty() || !file.isEmpty()) {
    title += QStringLiteral(" — ") + (name.isEmpty() ? tr("untitled map") : name);
    if (!file.isEmpty())
      title += QStringLiteral(" (%1)").arg(QFileInfo(file).fileName());
  }
  setWindowTitle(title);
  setWindowFilePath(file);
}

void MainWindow::updateSimulationActions() {
  const bool simulated = session_.simulationControl() != nullptr;
  const bool paused = session_.paused();
  run_pause_action_->setEnabled(simulated);
  run_pause_action_->setText(paused ? tr("&Run") : tr("&Pause"));
  step_action_->setEnabled(simulated);
  reset_robot_action_->setEnabled(simulated);
  speed_group_->setEnabled(simulated);
  for (QAction* action : speed_group_->actions())
    action->setChecked(action->data().toDouble() == session_.speedFactor());
  panel_->setSimulationControlsEnabled(simulated);
  panel_->setPaused(paused);
  panel_->setSimSpeed(session_.speedFactor());
  status_->refresh(session_);
}

void MainWindow::showShortcuts() {
  QString html = QStringLiteral("<table cellspacing='0' cellpadding='3'>");
  for (const shortcuts::Entry& entry : shortcuts::table()) {
    html += QStringLiteral("<tr><td><b>%1</b></td><td>%2</td></tr>")
                .arg(entry.keys.toHtmlEscaped(), entry.action.toHtmlEscaped());
  }
  html += QStringLiteral(
      "</table><p>Driving keys work whenever no text field has focus; "
      "speeds come from the command panel.</p>");
  QMessageBox box(QMessageBox::NoIcon, tr("Keyboard Shortcuts"), html, QMessageBox::Close, this);
  box.setTextFormat(Qt::RichText);
  box.exec();
}

void MainWindow::showAbout() {
  QMessageBox::about(
      this, tr("About IRGS"),
      tr("<b>IRGS %1</b> — Indoor Robot Ground Station<p>Map display, sonar occupancy mapping, "
         "simulator and teleoperation for small indoor robots.</p><p>Robot: %2</p>")
          .arg(QStringLiteral(IRGS_VERSION),
               session_.robot() != nullptr
                   ? QString::fromStdString(session_.robot()->describe()).toHtmlEscaped()
                   : tr("none")));
}

void MainWindow::fitSideColumnToTab(int index, bool grow_only) {
  QList<int> sizes = side_splitter_->sizes();
  QWidget* page = control_tabs_->widget(index);
  // Tabs, link-health panel (keeps its height), console.
  const int total = sizes.size() == 3 ? sizes[0] + sizes[2] : 0;
  if (page == nullptr || total <= 0)
    return;
  int wanted = 0;
  if (const auto chosen = user_tab_heights_.find(index); chosen != user_tab_heights_.end())
    wanted = chosen->second;
  else
    wanted = control_tabs_->tabBar()->sizeHint().height() + page->sizeHint().height() + 6;
  constexpr int kConsoleMinimum = 150;  // a few console lines stay visible
  const int lowest = control_tabs_->minimumSizeHint().height();
  const int tabs = std::clamp(wanted, lowest, std::max(lowest, total - kConsoleMinimum));
  if (tabs == sizes[0] || (grow_only && tabs < sizes[0]))
    return;
  sizes[0] = tabs;
  sizes[2] = total - tabs;
  side_splitter_->setSizes(sizes);
}

bool MainWindow::eventFilter(QObject* watched, QEvent* event) {
  // A page that grows (the editor's selection panel filled) gets the room, unless the user has
  // sized that tab's area by hand.
  // The pages' geometry changes reach their parent, the tab widget's stack, as layout requests.
  if (event->type() == QEvent::LayoutRequest &&
      watched == control_tabs_->currentWidget()->parent() &&
      !user_tab_heights_.contains(control_tabs_->currentIndex()))
    fitSideColumnToTab(control_tabs_->currentIndex(), true);
  return QMainWindow::eventFilter(watched, event);
}

void MainWindow::restoreSettings(const QSize& default_size) {
  if (!restoreGeometry(settings_.value(settingsKey(settings_key::kWindowGeometry)).toByteArray()))
    resize(default_size);
  restoreState(settings_.value(settingsKey(settings_key::kWindowState)).toByteArray());
  if (!main_splitter_->restoreState(
          settings_.value(settingsKey(settings_key::kMainSplitter)).toByteArray())) {
    main_splitter_->setSizes({std::max(400, width() - kSideColumnWidth), kSideColumnWidth});
  }
  // Command panel, link-health panel (hidden unless linked), console. A state saved before the
  // health panel existed has two sizes: lay out afresh then.
  if (!side_splitter_->restoreState(
          settings_.value(settingsKey(settings_key::kSideSplitter)).toByteArray()) ||
      side_splitter_->sizes().size() != 3 || side_splitter_->sizes().at(2) <= 0) {
    const int panel_height = control_tabs_->sizeHint().height();
    const int health_height = link_ui_->healthPanel().sizeHint().height();
    side_splitter_->setSizes(
        {panel_height, health_height, std::max(200, height() - panel_height - health_height)});
  }
  const double linear =
      settings_.value(settingsKey(settings_key::kLinearSpeed), panel_->linearSpeed()).toDouble();
  const double angular =
      settings_.value(settingsKey(settings_key::kAngularSpeed), panel_->angularSpeed()).toDouble();
  panel_->setDriveSpeeds(linear, angular);
  teleop_->setSpeeds(panel_->linearSpeed(), panel_->angularSpeed());
  follow_action_->setChecked(
      settings_.value(settingsKey(settings_key::kFollowRobot), false).toBool());
  settings_.beginGroup(settingsKey(settings_key::kLayerGroup));
  for (std::size_t i = 0; i < kLayers.size(); ++i)
    layer_actions_[i]->setChecked(
        settings_.value(QString::fromLatin1(kLayers[i].key), true).toBool());
  settings_.endGroup();
}

void MainWindow::saveSettings() {
  settings_.setValue(settingsKey(settings_key::kWindowGeometry), saveGeometry());
  settings_.setValue(settingsKey(settings_key::kWindowState), saveState());
  settings_.setValue(settingsKey(settings_key::kMainSplitter), main_splitter_->saveState());
  settings_.setValue(settingsKey(settings_key::kSideSplitter), side_splitter_->saveState());
  settings_.setValue(settingsKey(settings_key::kLinearSpeed), panel_->linearSpeed());
  settings_.setValue(settingsKey(settings_key::kAngularSpeed), panel_->angularSpeed());
  settings_.setValue(settingsKey(settings_key::kFollowRobot), follow_action_->isChecked());
  settings_.beginGroup(settingsKey(settings_key::kLayerGroup));
  for (std::size_t i = 0; i < kLayers.size(); ++i)
    settings_.setValue(QString::fromLatin1(kLayers[i].key), layer_actions_[i]->isChecked());
  settings_.endGroup();
  settings_.sync();
}

void MainWindow::refreshStatus() {
  status_->refresh(session_);
}

void MainWindow::closeEvent(QCloseEvent* event) {
  if (!editor_->confirmDiscard()) {  // unsaved map edits: the user chose Cancel
    event->ignore();
    return;
  }
  editor_->shutdown();
  session_.stopRobot();
  saveSettings();
  event->accept();
}

}  // namespace irgs::gui
