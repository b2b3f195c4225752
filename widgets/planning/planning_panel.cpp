#include "widgets/planning/planning_panel.hpp"

#include <QComboBox>
#include <QDoubleSpinBox>
#include <QGridLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QProgressBar>
#include <QPushButton>
#include <QSignalBlocker>
#include <QStandardItemModel>
#include <QTabWidget>
#include <QVBoxLayout>
#include <algorithm>
#include <cmath>

namespace irgs::widgets {
namespace {

const QString kDash = QStringLiteral("–");

QLabel* valueLabel(QWidget* parent, const QString& name) {
  auto* label = new QLabel(kDash, parent);
  label->setObjectName(name);
  label->setAlignment(Qt::AlignRight | Qt::AlignVCenter);
  label->setTextInteractionFlags(Qt::TextSelectableByMouse);
  return label;
}

QPushButton* button(QWidget* parent, const QString& name, const QString& text,
                    const QString& tooltip, bool checkable = false) {
  auto* b = new QPushButton(text, parent);
  b->setObjectName(name);
  b->setToolTip(tooltip);
  b->setCheckable(checkable);
  b->setFocusPolicy(Qt::NoFocus);  // keep the keyboard teleop's keys
  return b;
}

QString formatTime(double s) {
  if (!std::isfinite(s))
    return kDash;
  if (s < 60.0)
    return QStringLiteral("%1 s").arg(s, 0, 'f', 1);
  return QStringLiteral("%1 min %2 s")
      .arg(static_cast<int>(s / 60.0))
      .arg(std::fmod(s, 60.0), 0, 'f', 0);
}

}  // namespace

PlanningPanel::PlanningPanel(QWidget* parent) : QWidget(parent) {
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->setSpacing(4);

  auto* source_row = new QHBoxLayout;
  auto* source_label = new QLabel(tr("Plan on:"), this);
  source_combo_ = new QComboBox(this);
  source_combo_->setObjectName(QStringLiteral("planSource"));
  source_combo_->addItem(tr("Loaded map"), static_cast<int>(PlanSource::kWorldMap));
  source_combo_->addItem(tr("Sonar grid"), static_cast<int>(PlanSource::kSonarGrid));
  source_combo_->addItem(tr("Built map"), static_cast<int>(PlanSource::kBuiltMap));
  source_combo_->setToolTip(
      tr("The map the planners use: the loaded map, the live sonar occupancy grid, or the map "
         "built by map building (unknown cells count as blocked)"));
  source_label->setBuddy(source_combo_);
  source_row->addWidget(source_label);
  source_row->addWidget(source_combo_, 1);
  layout->addLayout(source_row);
  setPlanSourceAvailable(PlanSource::kBuiltMap, false);
  connect(source_combo_, &QComboBox::currentIndexChanged, this,
          [this] { emit planSourceChanged(planSource()); });

  tabs_ = new QTabWidget(this);
  tabs_->setObjectName(QStringLiteral("planningTabs"));
  tabs_->setDocumentMode(true);
  tabs_->addTab(buildGoalTab(), tr("Goal"));
  tabs_->addTab(buildCoverageTab(), tr("Coverage"));
  tabs_->addTab(buildMapBuildingTab(), tr("Map building"));
  layout->addWidget(tabs_);
  connect(tabs_, &QTabWidget::currentChanged, this,
          [this](int index) { emit currentTabChanged(static_cast<Tab>(index)); });
  updateButtons();
}

QWidget* PlanningPanel::buildGoalTab() {
  auto* tab = new QWidget(this);
  auto* layout = new QVBoxLayout(tab);
  layout->setContentsMargins(6, 6, 6, 4);
  auto* row = new QHBoxLayout;
  pick_goal_ = button(tab, QStringLiteral("pickGoal"), tr("Pick goal"),
                      tr("Click a goal on the map (Esc leaves the mode)"), true);
  drive_goal_ = button(tab, QStringLiteral("driveGoal"), tr("Drive"),
                       tr("Drive the amended path, turning on the spot at each turning point"));
  stop_goal_ = button(tab, QStringLiteral("stopGoal"), tr("Stop"), tr("Stop driving"));
  row->addWidget(pick_goal_);
  row->addWidget(drive_goal_);
  row->addWidget(stop_goal_);
  layout->addLayout(row);

  auto* grid = new QGridLayout;
  grid->setHorizontalSpacing(10);
  grid->setVerticalSpacing(2);
  const QStringList headers{QString(), tr("Turns"), tr("Length"), tr("Est. time")};
  for (int c = 0; c < headers.size(); ++c) {
    auto* h = new QLabel(QStringLiteral("<small><b>%1</b></small>").arg(headers[c]), tab);
    h->setAlignment(c == 0 ? Qt::AlignLeft : (Qt::AlignRight | Qt::AlignVCenter));
    grid->addWidget(h, 0, c);
  }
  auto* raw = new QLabel(tr("<span style='color:#e65100'>- - A* path</span>"), tab);
  raw->setToolTip(tr("The shortest 8-connected grid path (dashed orange on the map)"));
  auto* amended = new QLabel(tr("<span style='color:#00796b'><b>—</b> Amended</span>"), tab);
  amended->setToolTip(
      tr("After path amendment: fewer stop-and-turns, headings on the 15° quantum (solid teal)"));
  grid->addWidget(raw, 1, 0);
  grid->addWidget(amended, 2, 0);
  raw_turns_ = valueLabel(tab, QStringLiteral("rawTurns"));
  raw_length_ = valueLabel(tab, QStringLiteral("rawLength"));
  raw_time_ = valueLabel(tab, QStringLiteral("rawTime"));
  amended_turns_ = valueLabel(tab, QStringLiteral("amendedTurns"));
  amended_length_ = valueLabel(tab, QStringLiteral("amendedLength"));
  amended_time_ = valueLabel(tab, QStringLiteral("amendedTime"));
  grid->addWidget(raw_turns_, 1, 1);
  grid->addWidget(raw_length_, 1, 2);
  grid->addWidget(raw_time_, 1, 3);
  grid->addWidget(amended_turns_, 2, 1);
  grid->addWidget(amended_length_, 2, 2);
  grid->addWidget(amended_time_, 2, 3);
  grid->setColumnStretch(0, 1);
  layout->addLayout(grid);
  goal_note_ = new QLabel(tr("Pick a goal on the map."), tab);
  goal_note_->setObjectName(QStringLiteral("goalNote"));
  goal_note_->setWordWrap(true);
  layout->addWidget(goal_note_);
  layout->addStretch(1);

  connect(pick_goal_, &QPushButton::toggled, this, &PlanningPanel::pickGoalToggled);
  connect(drive_goal_, &QPushButton::clicked, this, &PlanningPanel::driveGoalRequested);
  connect(stop_goal_, &QPushButton::clicked, this, &PlanningPanel::stopRequested);
  return tab;
}

QWidget* PlanningPanel::buildCoverageTab() {
  auto* tab = new QWidget(this);
  auto* layout = new QVBoxLayout(tab);
  layout->setContentsMargins(6, 6, 6, 4);
  auto* row = new QHBoxLayout;
  select_region_ = button(tab, QStringLiteral("selectRegion"), tr("Select region"),
                          tr("Drag a rectangle on the map (Esc leaves the mode)"), true);
  drive_coverage_ =
      button(tab, QStringLiteral("driveCoverage"), tr("Drive"), tr("Drive the coverage path"));
  stop_coverage_ = button(tab, QStringLiteral("stopCoverage"), tr("Stop"), tr("Stop driving"));
  row->addWidget(select_region_);
  row->addWidget(drive_coverage_);
  row->addWidget(stop_coverage_);
  layout->addLayout(row);

  auto* settings = new QHBoxLayout;
  pattern_combo_ = new QComboBox(tab);
  pattern_combo_->setObjectName(QStringLiteral("coveragePattern"));
  pattern_combo_->addItem(tr("Spiral"), static_cast<int>(CoveragePattern::kSpiral));
  pattern_combo_->addItem(tr("Boustrophedon"), static_cast<int>(CoveragePattern::kBoustrophedon));
  pattern_combo_->setToolTip(
      tr("Spiral: from the outline inwards, as in the thesis; boustrophedon: back and forth"));
  lane_spin_ = new QDoubleSpinBox(tab);
  lane_spin_->setObjectName(QStringLiteral("laneWidth"));
  lane_spin_->setRange(0.05, 2.0);
  lane_spin_->setSingleStep(0.05);
  lane_spin_->setDecimals(2);
  lane_spin_->setSuffix(tr(" m"));
  lane_spin_->setValue(0.25);
  lane_spin_->setToolTip(tr("Lane spacing: a little less than the robot's cleaning width"));
  auto* lane_label = new QLabel(tr("Lanes"), tab);
  lane_label->setBuddy(lane_spin_);
  settings->addWidget(pattern_combo_, 1);
  settings->addWidget(lane_label);
  settings->addWidget(lane_spin_);
  layout->addLayout(settings);

  coverage_summary_ = new QLabel(tr("Select a region on the map."), tab);
  coverage_summary_->setObjectName(QStringLiteral("coverageSummary"));
  coverage_summary_->setWordWrap(true);
  layout->addWidget(coverage_summary_);
  coverage_bar_ = new QProgressBar(tab);
  coverage_bar_->setObjectName(QStringLiteral("coverageBar"));
  coverage_bar_->setRange(0, 1000);
  coverage_bar_->setValue(0);
  coverage_bar_->setFormat(tr("Swept: –"));
  coverage_bar_->setToolTip(
      tr("Cells of the region the robot's body has passed over, of those it can reach"));
  layout->addWidget(coverage_bar_);
  layout->addStretch(1);

  connect(select_region_, &QPushButton::toggled, this, &PlanningPanel::selectRegionToggled);
  connect(drive_coverage_, &QPushButton::clicked, this, &PlanningPanel::driveCoverageRequested);
  connect(stop_coverage_, &QPushButton::clicked, this, &PlanningPanel::stopRequested);
  connect(pattern_combo_, &QComboBox::currentIndexChanged, this,
          &PlanningPanel::coverageSettingsChanged);
  connect(lane_spin_, &QDoubleSpinBox::valueChanged, this, &PlanningPanel::coverageSettingsChanged);
  return tab;
}

QWidget* PlanningPanel::buildMapBuildingTab() {
  auto* tab = new QWidget(this);
  auto* layout = new QVBoxLayout(tab);
  layout->setContentsMargins(6, 6, 6, 4);
  auto* row = new QHBoxLayout;
  build_start_ = button(tab, QStringLiteral("mapBuildStart"), tr("Start"),
                        tr("Build a map: seek a wall, follow it round, explore the inside"));
  build_pause_ = button(tab, QStringLiteral("mapBuildPause"), tr("Pause"),
                        tr("Stop the robot and hold map building"), true);
  build_abort_ = button(tab, QStringLiteral("mapBuildAbort"), tr("Abort"),
                        tr("Stop map building (the map so far is kept)"));
  row->addWidget(build_start_);
  row->addWidget(build_pause_);
  row->addWidget(build_abort_);
  layout->addLayout(row);
  build_phase_ = new QLabel(tr("Phase: idle"), tab);
  build_phase_->setObjectName(QStringLiteral("mapBuildPhase"));
  build_phase_->setWordWrap(true);
  layout->addWidget(build_phase_);
  build_bar_ = new QProgressBar(tab);
  build_bar_->setObjectName(QStringLiteral("mapBuildProgress"));
  build_bar_->setRange(0, 1000);
  build_bar_->setValue(0);
  build_bar_->setFormat(QStringLiteral("%p%"));
  layout->addWidget(build_bar_);
  build_save_ = button(tab, QStringLiteral("saveBuiltMap"), tr("Save built map…"),
                       tr("Write the built grid as a ROS map (PGM + YAML)"));
  layout->addWidget(build_save_, 0, Qt::AlignLeft);
  layout->addStretch(1);

  connect(build_start_, &QPushButton::clicked, this, &PlanningPanel::mapBuildStartRequested);
  connect(build_pause_, &QPushButton::toggled, this, &PlanningPanel::mapBuildPauseToggled);
  connect(build_abort_, &QPushButton::clicked, this, &PlanningPanel::mapBuildAbortRequested);
  connect(build_save_, &QPushButton::clicked, this, &PlanningPanel::saveBuiltMapRequested);
  return tab;
}

PlanSource PlanningPanel::planSource() const {
  return static_cast<PlanSource>(source_combo_->currentData().toInt());
}

void PlanningPanel::setPlanSource(PlanSource source) {
  const QSignalBlocker block(source_combo_);
  const int index = source_combo_->findData(static_cast<int>(source));
  if (index >= 0)
    source_combo_->setCurrentIndex(index);
}

void PlanningPanel::setPlanSourceAvailable(PlanSource source, bool available) {
  auto* model = qobject_cast<QStandardItemModel*>(source_combo_->model());
  const int index = source_combo_->findData(static_cast<int>(source));
  if (model == nullptr || index < 0)
    return;
  model->item(index)->setEnabled(available);
  if (!available && source_combo_->currentIndex() == index) {
    const QSignalBlocker block(source_combo_);
    source_combo_->setCurrentIndex(0);
  }
}

PlanningPanel::Tab PlanningPanel::currentTab() const {
  return static_cast<Tab>(tabs_->currentIndex());
}

void PlanningPanel::setCurrentTab(Tab tab) {
  const QSignalBlocker block(tabs_);
  tabs_->setCurrentIndex(static_cast<int>(tab));
}

void PlanningPanel::setGoalPreview(const std::optional<PathStats>& raw,
                                   const std::optional<PathStats>& amended, const QString& note) {
  auto show = [](const std::optional<PathStats>& s, QLabel* turns, QLabel* length, QLabel* time) {
    turns->setText(s ? QString::number(s->turns) : kDash);
    length->setText(s ? QStringLiteral("%1 m").arg(s->length_m, 0, 'f', 2) : kDash);
    time->setText(s ? formatTime(s->time_s) : kDash);
  };
  show(raw, raw_turns_, raw_length_, raw_time_);
  show(amended, amended_turns_, amended_length_, amended_time_);
  goal_note_->setText(note);
}

void PlanningPanel::setPickGoalChecked(bool checked) {
  const QSignalBlocker block(pick_goal_);
  pick_goal_->setChecked(checked);
}

bool PlanningPanel::pickGoalChecked() const {
  return pick_goal_->isChecked();
}

CoveragePattern PlanningPanel::coveragePattern() const {
  return static_cast<CoveragePattern>(pattern_combo_->currentData().toInt());
}

double PlanningPanel::laneWidth() const {
  return lane_spin_->value();
}

void PlanningPanel::setLaneWidth(double lane_m) {
  if (!std::isfinite(lane_m))
    return;
  const QSignalBlocker block(lane_spin_);
  lane_spin_->setValue(lane_m);
}

void PlanningPanel::setSelectRegionChecked(bool checked) {
  const QSignalBlocker block(select_region_);
  select_region_->setChecked(checked);
}

bool PlanningPanel::selectRegionChecked() const {
  return select_region_->isChecked();
}

void PlanningPanel::setCoverageSummary(const QString& text) {
  coverage_summary_->setText(text);
}

void PlanningPanel::setCoverage(std::optional<double> fraction) {
  if (!fraction || !std::isfinite(*fraction)) {
    coverage_bar_->setValue(0);
    coverage_bar_->setFormat(tr("Swept: –"));
    return;
  }
  const double f = std::clamp(*fraction, 0.0, 1.0);
  coverage_bar_->setValue(static_cast<int>(std::lround(f * 1000.0)));
  coverage_bar_->setFormat(tr("Swept: %1 %").arg(f * 100.0, 0, 'f', 1));
}

void PlanningPanel::setMapBuildStatus(const QString& phase, double progress) {
  build_phase_->setText(tr("Phase: %1").arg(phase.isEmpty() ? tr("idle") : phase));
  const double p = std::isfinite(progress) ? std::clamp(progress, 0.0, 1.0) : 0.0;
  build_bar_->setValue(static_cast<int>(std::lround(p * 1000.0)));
}

void PlanningPanel::setBuiltMapAvailable(bool available) {
  built_map_ = available;
  setPlanSourceAvailable(PlanSource::kBuiltMap, available);
  updateButtons();
}

void PlanningPanel::setMapBuildingAvailable(bool available, const QString& why_not) {
  map_building_available_ = available;
  build_start_->setToolTip(available ? tr("Build a map: seek a wall, follow it round, explore "
                                          "the inside")
                                     : why_not);
  updateButtons();
}

void PlanningPanel::setRunningTask(Task task, bool paused) {
  running_ = task;
  paused_ = paused;
  updateButtons();
}

void PlanningPanel::setGoalDrivable(bool drivable) {
  goal_drivable_ = drivable;
  updateButtons();
}

void PlanningPanel::setCoverageDrivable(bool drivable) {
  coverage_drivable_ = drivable;
  updateButtons();
}

void PlanningPanel::updateButtons() {
  const bool idle = running_ == Task::kNone;
  drive_goal_->setEnabled(idle && goal_drivable_);
  stop_goal_->setEnabled(running_ == Task::kGoal);
  drive_coverage_->setEnabled(idle && coverage_drivable_);
  stop_coverage_->setEnabled(running_ == Task::kCoverage);
  const bool building = running_ == Task::kMapBuilding;
  build_start_->setEnabled(idle && map_building_available_);
  build_pause_->setEnabled(building);
  {
    const QSignalBlocker block(build_pause_);
    build_pause_->setChecked(building && paused_);
    build_pause_->setText(building && paused_ ? tr("Resume") : tr("Pause"));
  }
  build_abort_->setEnabled(building);
  build_save_->setEnabled(built_map_);
}

}  // namespace irgs::widgets
