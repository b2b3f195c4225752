#pragma once
// The command panel: robot mode (simulator / linked robot), a press-and-hold drive pad with
// speed settings, simulation controls (run/pause, step, speed factor) and, for a linked robot,
// the firmware behaviours (move a distance, turn an angle).
//
// Setters never emit signals (so the owner can mirror state without feedback loops); signals
// are emitted only for user actions.

#include <QString>
#include <QWidget>

class QButtonGroup;
class QComboBox;
class QDoubleSpinBox;
class QGroupBox;
class QRadioButton;
class QToolButton;
class QVBoxLayout;

namespace irgs::widgets {

enum class RobotMode { kSimulator, kLinkedRobot };
enum class DriveIcon;

class CommandPanel : public QWidget {
  Q_OBJECT

 public:
  // Spin box ranges of the drive speeds.
  static constexpr double kMaxLinear_mps = 2.0;
  static constexpr double kMaxAngular_degps = 360.0;

  explicit CommandPanel(QWidget* parent = nullptr);

  void setMode(RobotMode mode);
  RobotMode mode() const;
  // Disables the "Robot link" choice, with `why_not` as its tooltip, when not available.
  void setLinkedModeAvailable(bool available, const QString& why_not);
  void setSimulationControlsEnabled(bool enabled);
  // Shows the robot-behaviour group (linked robots run behaviours in their firmware).
  void setBehavioursVisible(bool visible);
  bool behavioursVisible() const;
  // The distance (m, signed) and angle (rad, CCW positive) the behaviour buttons ask for.
  double behaviourDistance() const;
  double behaviourAngle() const;
  void setPaused(bool paused);
  bool paused() const;
  // 1, 2, 10 or 0 (= as fast as possible); other positive factors get their own entry.
  void setSimSpeed(double factor);
  double simSpeed() const;
  // Speeds used by the drive pad (and shown for the keyboard teleop). Non-finite or negative
  // values are ignored; values are clamped to the spin box ranges.
  void setDriveSpeeds(double linear_mps, double angular_radps);
  // Adds a group below the panel's own (the drive pad and gamepad status, app/gui).
  void addSection(QWidget* section);
  double linearSpeed() const;   // m/s
  double angularSpeed() const;  // rad/s

 signals:
  void modeRequested(irgs::widgets::RobotMode mode);
  // While a drive button is held: its command; on release: (0, 0).
  void driveRequested(double linear_mps, double angular_radps);
  void stopRequested();
  void pausedChanged(bool paused);
  void stepRequested();
  void simSpeedChanged(double factor);  // 1, 2, 10, 0 (= max)
  void driveSpeedsChanged(double linear_mps, double angular_radps);
  void moveDistanceRequested(double distance_m);  // signed: negative reverses
  void turnAngleRequested(double angle_rad);      // counter-clockwise positive

 private:
  // Direction of a drive button: multipliers of the linear and angular speed.
  struct Drive {
    int linear = 0;
    int angular = 0;
  };

  QGroupBox* buildModeGroup();
  QGroupBox* buildDriveGroup();
  QGroupBox* buildSimulationGroup();
  QGroupBox* buildBehaviourGroup();
  QToolButton* makeDriveButton(Drive drive, DriveIcon icon, const QString& tooltip);
  void emitHeldDrive();
  void updatePauseButton();

  QVBoxLayout* column_ = nullptr;  // the groups, inside the panel's scroll column
  QRadioButton* sim_radio_ = nullptr;
  QRadioButton* link_radio_ = nullptr;
  QButtonGroup* mode_group_ = nullptr;
  QDoubleSpinBox* linear_spin_ = nullptr;
  QDoubleSpinBox* angular_spin_ = nullptr;  // deg/s
  QToolButton* stop_button_ = nullptr;
  QGroupBox* sim_group_ = nullptr;
  QToolButton* pause_button_ = nullptr;
  QToolButton* step_button_ = nullptr;
  QComboBox* speed_combo_ = nullptr;
  QGroupBox* behaviour_group_ = nullptr;
  QDoubleSpinBox* move_spin_ = nullptr;  // m
  QDoubleSpinBox* turn_spin_ = nullptr;  // deg
  bool held_ = false;
  Drive held_drive_;
};

}  // namespace irgs::widgets
