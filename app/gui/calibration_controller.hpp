#pragma once
// The Calibrate menu: opens the UMBmark and gyro wizards (widgets/calibration) for the session's
// robot profile, and drives the UMBmark squares a wizard asks for on the session's robot
// (simulated or linked) through a BehaviourController, so the square runs through the one Robot
// interface like every other behaviour. Refuses while another behaviour or drive script holds
// the robot's commands.

#include <QObject>
#include <QPointer>
#include <QString>

#include "core/calibration/umbmark_square.hpp"

class QMainWindow;
class QMenu;

namespace irgs::widgets {
class GyroWizard;
class UmbmarkWizard;
}  // namespace irgs::widgets

namespace irgs::gui {

class BehaviourController;
class SessionController;

class CalibrationController : public QObject {
  Q_OBJECT

 public:
  // `profile_file`: the profile the session uses, the wizards' default output.
  CalibrationController(QMainWindow& window, SessionController& session, QString profile_file,
                        QObject* parent = nullptr);
  ~CalibrationController() override;

  QMenu* menu() const { return menu_; }
  widgets::UmbmarkWizard* openUmbmarkWizard();
  widgets::GyroWizard* openGyroWizard();
  // Drives one square on the session's robot and reports it to the UMBmark wizard.
  void driveSquare(const UmbmarkSquareConfig& config);
  bool squareRunning() const;

 private:
  void onSquareFinished(bool failed, const QString& message);

  QMainWindow& window_;
  SessionController& session_;
  QString profile_file_;
  QMenu* menu_ = nullptr;
  BehaviourController* behaviours_ = nullptr;
  QPointer<widgets::UmbmarkWizard> umbmark_;
  QPointer<widgets::GyroWizard> gyro_;
  UmbmarkSquareBehaviour* square_ = nullptr;  // owned by behaviours_, valid while it runs
  UmbmarkDirection square_direction_ = UmbmarkDirection::kClockwise;
};

}  // namespace irgs::gui
