#pragma once
// The UMBmark odometry calibration wizard (docs/calibration.md): the 4 m square driven clockwise
// and counter-clockwise, then the wheel-diameter ratio and wheelbase corrections (core/
// calibration), written back to the robot profile atomically.
//
// Two sources of runs:
//  - Simulator: the procedure runs in-process on the profile with injected wheel-diameter and
//    wheelbase errors; the return errors come from the simulator's truth, and a verification
//    re-run on the corrected odometry shows the improvement of E_max,syst.
//  - Robot: the wizard asks the application to drive one square on the session's robot (through
//    the Robot interface, simulated or linked: driveSquareRequested), the application reports
//    the robot's believed end (addRobotRun) and the user types the measured end position into
//    the table (a robot that reports truth, the session simulator, pre-fills it).
// The wizard is a plain QDialog: it knows no session and no link.

#include <QDialog>
#include <QString>
#include <optional>

#include "core/calibration/umbmark_procedure.hpp"
#include "core/calibration/umbmark_square.hpp"
#include "core/robot/robot_profile.hpp"

class QComboBox;
class QDoubleSpinBox;
class QLabel;
class QLineEdit;
class QPlainTextEdit;
class QPushButton;
class QSpinBox;
class QStackedWidget;
class QTableWidget;

namespace irgs::widgets {

class UmbmarkPathView;

class UmbmarkWizard : public QDialog {
  Q_OBJECT

 public:
  enum class Source { kSimulator = 0, kRobot = 1 };

  // `profile_file`: where "Write profile" saves by default (the profile the robot uses).
  UmbmarkWizard(RobotProfile profile, const QString& profile_file, QWidget* parent = nullptr);

  void setSource(Source source);
  Source source() const;
  void setInjection(const UmbmarkInjection& injection);
  void setSide(double side_m);
  void setRunsPerDirection(int runs);
  void setSeed(int seed);
  void setOutputFile(const QString& path);
  QString outputFile() const;

  // Runs the simulated procedure (blocking; a few seconds at most) and shows the result.
  void runSimulation();
  // Robot source: one square the application drove. `odometry_end` is the robot's believed end
  // in the start frame; `true_end` pre-fills the measured cells when the robot reports truth.
  void addRobotRun(UmbmarkDirection direction, const Vec2& odometry_end,
                   const std::optional<Vec2>& true_end);
  // Robot source: the application could not drive the square (reason shown).
  void robotRunFailed(const QString& reason);
  // Robot source: analyses the runs in the table (measured - odometry ends).
  void analyseRobotRuns();
  // Saves the corrected profile to outputFile(); false (and a message) on error.
  bool writeProfile();

  const std::optional<UmbmarkProcedureResult>& result() const { return result_; }
  QString resultText() const;
  int robotRunCount() const;
  QString robotStatusText() const;

 signals:
  // Robot source: drive one square on the session's robot with this configuration.
  void driveSquareRequested(const irgs::UmbmarkSquareConfig& config);
  // A corrected profile was written.
  void profileWritten(const QString& path);

 private:
  void showResult();
  void setBusy(bool busy);
  UmbmarkSquareConfig squareConfig(UmbmarkDirection direction) const;

  RobotProfile profile_;
  std::optional<UmbmarkInjection> injected_;  // of the shown simulated result
  std::optional<UmbmarkProcedureResult> result_;

  QComboBox* source_ = nullptr;
  QStackedWidget* pages_ = nullptr;
  QDoubleSpinBox* side_ = nullptr;
  QSpinBox* runs_ = nullptr;
  QSpinBox* seed_ = nullptr;
  QDoubleSpinBox* inject_ed_ = nullptr;
  QDoubleSpinBox* inject_eb_ = nullptr;
  QDoubleSpinBox* inject_slip_ = nullptr;
  QPushButton* run_sim_ = nullptr;
  QTableWidget* table_ = nullptr;
  QPushButton* drive_cw_ = nullptr;
  QPushButton* drive_ccw_ = nullptr;
  QPushButton* analyse_ = nullptr;
  QLabel* robot_status_ = nullptr;
  UmbmarkPathView* paths_ = nullptr;
  QPlainTextEdit* report_ = nullptr;
  QLineEdit* output_ = nullptr;
  QPushButton* write_ = nullptr;
  QLabel* write_status_ = nullptr;
};

}  // namespace irgs::widgets
