#include "widgets/command/command_panel.hpp"

#include <QButtonGroup>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QGridLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QRadioButton>
#include <QSignalBlocker>
#include <QStyle>
#include <QToolButton>
#include <QVBoxLayout>
#include <cmath>

#include "core/geometry/types.hpp"
#include "widgets/command/drive_icons.hpp"
#include "widgets/layout/scroll_column.hpp"

namespace irgs::widgets {
namespace {

constexpr int kPadButton_px = 46;
const QColor kIconColour(38, 50, 56);

QString linkedAvailableTip() {
  return QObject::tr("Drive a real robot over its serial / network link");
}

}  // namespace

CommandPanel::CommandPanel(QWidget* parent) : QWidget(parent) {
  // Linked, with the behaviours and the pad, taller than a laptop screen leaves the side column:
  // it scrolls (ScrollColumn says why).
  auto* outer = new QVBoxLayout(this);
  outer->setContentsMargins(0, 0, 0, 0);
  auto* scroll = new ScrollColumn(this);
  scroll->setObjectName(QStringLiteral("commandScroll"));
  outer->addWidget(scroll);
  column_ = &scroll->column();
  QVBoxLayout* layout = column_;
  layout->setContentsMargins(6, 6, 6, 6);
  layout->setSpacing(8);
  layout->addWidget(buildModeGroup());
  layout->addWidget(buildDriveGroup());
  layout->addWidget(buildSimulationGroup());
  layout->addWidget(buildBehaviourGroup());
  layout->addStretch(1);
  setSizePolicy(QSizePolicy::Preferred, QSizePolicy::Preferred);
}

QGroupBox* CommandPanel::buildModeGroup() {
  auto* group = new QGroupBox(tr("Mode"), this);
  sim_radio_ = new QRadioButton(tr("Simulator"), group);
  sim_radio_->setObjectName(QStringLiteral("modeSimulator"));
  sim_radio_->setToolTip(tr("Drive the simulated robot in the loaded map"));
  link_radio_ = new QRadioButton(tr("Robot link"), group);
  link_radio_->setObjectName(QStringLiteral("modeLinked"));
  link_radio_->setToolTip(linkedAvailableTip());
  sim_radio_->setChecked(true);
  mode_group_ = new QButtonGroup(group);
  mode_group_->addButton(sim_radio_, static_cast<int>(RobotMode::kSimulator));
  mode_group_->addButton(link_radio_, static_cast<int>(RobotMode::kLinkedRobot));
  connect(mode_group_, &QButtonGroup::idClicked, this,
          [this](int id) { emit modeRequested(static_cast<RobotMode>(id)); });
  auto* row = new QHBoxLayout(group);
  row->addWidget(sim_radio_);
  row->addWidget(link_radio_);
  row->addStretch(1);
  return group;
}

QToolButton* CommandPanel::makeDriveButton(Drive drive, DriveIcon icon, const QString& tooltip) {
  auto* button = new QToolButton(this);
  button->setIcon(makeDriveIcon(icon, kIconColour));
  button->setIconSize(QSize(26, 26));
  button->setFixedSize(kPadButton_px, kPadButton_px);
  button->setToolTip(tooltip);
  button->setFocusPolicy(Qt::NoFocus);  // keep keyboard focus where the teleop can use it
  connect(button, &QToolButton::pressed, this, [this, drive] {
    held_ = true;
    held_drive_ = drive;
    emitHeldDrive();
  });
  connect(button, &QToolButton::released, this, [this] {
    held_ = false;
    emit driveRequested(0.0, 0.0);
  });
  return button;
}

QGroupBox* CommandPanel::buildDriveGroup() {
  auto* group = new QGroupBox(tr("Drive"), this);
  auto* pad = new QGridLayout;
  pad->setSpacing(4);
  struct PadEntry {
    int row, col;
    Drive drive;
    DriveIcon icon;
    QString tip;
    const char* name;
  };
  const PadEntry entries[] = {
      {0,
       0,
       {1, 1},
       DriveIcon::kArcForwardLeft,
       tr("Forward, curving left (Up+Left / W+A)"),
       "driveForwardLeft"},
      {0, 1, {1, 0}, DriveIcon::kForward, tr("Forward (Up / W)"), "driveForward"},
      {0,
       2,
       {1, -1},
       DriveIcon::kArcForwardRight,
       tr("Forward, curving right (Up+Right / W+D)"),
       "driveForwardRight"},
      {1, 0, {0, 1}, DriveIcon::kTurnLeft, tr("Turn left on the spot (Left / A)"), "driveTurnLeft"},
      {1,
       2,
       {0, -1},
       DriveIcon::kTurnRight,
       tr("Turn right on the spot (Right / D)"),
       "driveTurnRight"},
      // Reversing like a car: "back-left" swings the rear to the left (heading turns clockwise).
      {2,
       0,
       {-1, -1},
       DriveIcon::kArcBackLeft,
       tr("Reverse, rear swinging left (Down+Left)"),
       "driveBackLeft"},
      {2, 1, {-1, 0}, DriveIcon::kBack, tr("Reverse (Down / S)"), "driveBack"},
      {2,
       2,
       {-1, 1},
       DriveIcon::kArcBackRight,
       tr("Reverse, rear swinging right (Down+Right)"),
       "driveBackRight"},
  };
  for (const PadEntry& e : entries) {
    QToolButton* button = makeDriveButton(e.drive, e.icon, e.tip + tr(" — hold to drive"));
    button->setObjectName(QLatin1String(e.name));
    pad->addWidget(button, e.row, e.col);
  }

  stop_button_ = new QToolButton(this);
  stop_button_->setObjectName(QStringLiteral("driveStop"));
  stop_button_->setText(tr("STOP"));
  stop_button_->setToolTip(tr("Stop the robot now (Space)"));
  stop_button_->setFixedSize(kPadButton_px, kPadButton_px);
  stop_button_->setFocusPolicy(Qt::NoFocus);
  stop_button_->setStyleSheet(QStringLiteral(
      "QToolButton { background: #d32f2f; color: white; font-weight: bold; font-size: 11px;"
      " border: 1px solid #9a0007; border-radius: 8px; }"
      "QToolButton:hover { background: #e53935; }"
      "QToolButton:pressed { background: #b71c1c; }"
      "QToolButton:disabled { background: #e8a3a3; border-color: #d49a9a; }"));
  connect(stop_button_, &QToolButton::clicked, this, [this] {
    held_ = false;
    emit stopRequested();
  });
  pad->addWidget(stop_button_, 1, 1);

  linear_spin_ = new QDoubleSpinBox(group);
  linear_spin_->setObjectName(QStringLiteral("driveLinearSpeed"));
  linear_spin_->setRange(0.01, kMaxLinear_mps);
  linear_spin_->setSingleStep(0.05);
  linear_spin_->setDecimals(2);
  linear_spin_->setSuffix(tr(" m/s"));
  linear_spin_->setValue(0.20);
  linear_spin_->setToolTip(tr("Speed of the drive buttons and the keyboard"));
  angular_spin_ = new QDoubleSpinBox(group);
  angular_spin_->setObjectName(QStringLiteral("driveAngularSpeed"));
  angular_spin_->setRange(1.0, kMaxAngular_degps);
  angular_spin_->setSingleStep(5.0);
  angular_spin_->setDecimals(0);
  angular_spin_->setSuffix(tr(" °/s"));
  angular_spin_->setValue(45.0);
  angular_spin_->setToolTip(tr("Turn rate of the drive buttons and the keyboard"));
  for (QDoubleSpinBox* spin : {linear_spin_, angular_spin_}) {
    spin->setKeyboardTracking(false);
    spin->setAlignment(Qt::AlignRight);
    connect(spin, &QDoubleSpinBox::valueChanged, this, [this] {
      emit driveSpeedsChanged(linearSpeed(), angularSpeed());
      if (held_)
        emitHeldDrive();
    });
  }

  auto* speeds = new QFormLayout;
  speeds->setFieldGrowthPolicy(QFormLayout::AllNonFixedFieldsGrow);
  speeds->addRow(tr("Linear"), linear_spin_);
  speeds->addRow(tr("Angular"), angular_spin_);

  auto* pad_row = new QHBoxLayout;
  pad_row->addStretch(1);
  pad_row->addLayout(pad);
  pad_row->addStretch(1);
  auto* column = new QVBoxLayout(group);
  column->addLayout(pad_row);
  column->addLayout(speeds);
  return group;
}

QGroupBox* CommandPanel::buildSimulationGroup() {
  sim_group_ = new QGroupBox(tr("Simulation"), this);
  pause_button_ = new QToolButton(sim_group_);
  pause_button_->setObjectName(QStringLiteral("simPause"));
  pause_button_->setCheckable(true);
  pause_button_->setToolButtonStyle(Qt::ToolButtonTextBesideIcon);
  pause_button_->setMinimumWidth(84);
  connect(pause_button_, &QToolButton::toggled, this, [this](bool paused) {
    updatePauseButton();
    emit pausedChanged(paused);
  });

  step_button_ = new QToolButton(sim_group_);
  step_button_->setObjectName(QStringLiteral("simStep"));
  step_button_->setText(tr("Step"));
  step_button_->setIcon(style()->standardIcon(QStyle::SP_MediaSkipForward));
  step_button_->setToolButtonStyle(Qt::ToolButtonTextBesideIcon);
  step_button_->setToolTip(tr("Advance one simulator step (while paused)"));
  connect(step_button_, &QToolButton::clicked, this, &CommandPanel::stepRequested);

  speed_combo_ = new QComboBox(sim_group_);
  speed_combo_->setObjectName(QStringLiteral("simSpeed"));
  speed_combo_->setToolTip(tr("Simulation speed relative to wall time"));
  speed_combo_->addItem(QStringLiteral("×1"), 1.0);
  speed_combo_->addItem(QStringLiteral("×2"), 2.0);
  speed_combo_->addItem(QStringLiteral("×10"), 10.0);
  speed_combo_->addItem(tr("max"), 0.0);
  connect(speed_combo_, &QComboBox::currentIndexChanged, this,
          [this] { emit simSpeedChanged(simSpeed()); });

  auto* row = new QHBoxLayout(sim_group_);
  row->addWidget(pause_button_);
  row->addWidget(step_button_);
  row->addStretch(1);
  row->addWidget(speed_combo_);
  updatePauseButton();
  return sim_group_;
}

QGroupBox* CommandPanel::buildBehaviourGroup() {
  behaviour_group_ = new QGroupBox(tr("Robot behaviours"), this);
  behaviour_group_->setObjectName(QStringLiteral("behaviours"));
  behaviour_group_->setToolTip(
      tr("Run by the robot's firmware on its odometry; STOP (Space) cancels them"));
  move_spin_ = new QDoubleSpinBox(behaviour_group_);
  move_spin_->setObjectName(QStringLiteral("behaviourDistance"));
  move_spin_->setRange(-10.0, 10.0);
  move_spin_->setSingleStep(0.1);
  move_spin_->setDecimals(2);
  move_spin_->setSuffix(tr(" m"));
  move_spin_->setValue(1.0);
  move_spin_->setToolTip(tr("Distance to drive straight (negative: reverse)"));
  turn_spin_ = new QDoubleSpinBox(behaviour_group_);
  turn_spin_->setObjectName(QStringLiteral("behaviourAngle"));
  turn_spin_->setRange(-720.0, 720.0);
  turn_spin_->setSingleStep(15.0);
  turn_spin_->setDecimals(0);
  turn_spin_->setSuffix(tr(" °"));
  turn_spin_->setValue(90.0);
  turn_spin_->setToolTip(tr("Angle to turn on the spot (positive: to the left)"));
  auto* move_button = new QToolButton(behaviour_group_);
  move_button->setObjectName(QStringLiteral("behaviourMove"));
  move_button->setText(tr("Move"));
  move_button->setFocusPolicy(Qt::NoFocus);
  move_button->setMinimumWidth(64);
  auto* turn_button = new QToolButton(behaviour_group_);
  turn_button->setObjectName(QStringLiteral("behaviourTurn"));
  turn_button->setText(tr("Turn"));
  turn_button->setFocusPolicy(Qt::NoFocus);
  turn_button->setMinimumWidth(64);
  connect(move_button, &QToolButton::clicked, this,
          [this] { emit moveDistanceRequested(behaviourDistance()); });
  connect(turn_button, &QToolButton::clicked, this,
          [this] { emit turnAngleRequested(behaviourAngle()); });
  for (QDoubleSpinBox* spin : {move_spin_, turn_spin_}) {
    spin->setKeyboardTracking(false);
    spin->setAlignment(Qt::AlignRight);
  }
  auto* grid = new QGridLayout(behaviour_group_);
  grid->addWidget(move_button, 0, 0);
  grid->addWidget(move_spin_, 0, 1);
  grid->addWidget(turn_button, 1, 0);
  grid->addWidget(turn_spin_, 1, 1);
  grid->setColumnStretch(1, 1);
  behaviour_group_->setVisible(false);
  return behaviour_group_;
}

void CommandPanel::updatePauseButton() {
  const bool paused = pause_button_->isChecked();
  pause_button_->setText(paused ? tr("Run") : tr("Pause"));
  pause_button_->setIcon(
      style()->standardIcon(paused ? QStyle::SP_MediaPlay : QStyle::SP_MediaPause));
  pause_button_->setToolTip(paused ? tr("Resume the simulation") : tr("Pause the simulation"));
  step_button_->setEnabled(paused);
}

void CommandPanel::emitHeldDrive() {
  emit driveRequested(held_drive_.linear * linearSpeed(), held_drive_.angular * angularSpeed());
}

void CommandPanel::setMode(RobotMode mode) {
  const QSignalBlocker block(mode_group_);
  (mode == RobotMode::kSimulator ? sim_radio_ : link_radio_)->setChecked(true);
}

RobotMode CommandPanel::mode() const {
  return link_radio_->isChecked() ? RobotMode::kLinkedRobot : RobotMode::kSimulator;
}

void CommandPanel::setLinkedModeAvailable(bool available, const QString& why_not) {
  link_radio_->setEnabled(available);
  link_radio_->setToolTip(available
                              ? linkedAvailableTip()
                              : (why_not.isEmpty() ? tr("No robot link available") : why_not));
}

void CommandPanel::setSimulationControlsEnabled(bool enabled) {
  sim_group_->setEnabled(enabled);
}

void CommandPanel::setBehavioursVisible(bool visible) {
  behaviour_group_->setVisible(visible);
}

bool CommandPanel::behavioursVisible() const {
  return !behaviour_group_->isHidden();
}

double CommandPanel::behaviourDistance() const {
  return move_spin_->value();
}

double CommandPanel::behaviourAngle() const {
  return degToRad(turn_spin_->value());
}

void CommandPanel::setPaused(bool paused) {
  {
    const QSignalBlocker block(pause_button_);
    pause_button_->setChecked(paused);
  }
  updatePauseButton();
}

bool CommandPanel::paused() const {
  return pause_button_->isChecked();
}

void CommandPanel::setSimSpeed(double factor) {
  if (!std::isfinite(factor) || factor < 0.0)
    return;
  const QSignalBlocker block(speed_combo_);
  int index = -1;
  for (int i = 0; i < speed_combo_->count(); ++i) {
    if (std::abs(speed_combo_->itemData(i).toDouble() - factor) < 1e-9)
      index = i;
  }
  if (index < 0) {  // an unusual factor (e.g. from the command line) gets its own entry
    index = speed_combo_->count() - 1;  // before "max"
    speed_combo_->insertItem(index, QStringLiteral("×%1").arg(factor), factor);
  }
  speed_combo_->setCurrentIndex(index);
}

double CommandPanel::simSpeed() const {
  return speed_combo_->currentData().toDouble();
}

void CommandPanel::addSection(QWidget* section) {
  column_->insertWidget(column_->count() - 1, section);  // above the closing stretch
}

void CommandPanel::setDriveSpeeds(double linear_mps, double angular_radps) {
  if (std::isfinite(linear_mps) && linear_mps >= 0.0) {
    const QSignalBlocker block(linear_spin_);
    linear_spin_->setValue(linear_mps);
  }
  if (std::isfinite(angular_radps) && angular_radps >= 0.0) {
    const QSignalBlocker block(angular_spin_);
    angular_spin_->setValue(radToDeg(angular_radps));
  }
}

double CommandPanel::linearSpeed() const {
  return linear_spin_->value();
}

double CommandPanel::angularSpeed() const {
  return degToRad(angular_spin_->value());
}

}  // namespace irgs::widgets
