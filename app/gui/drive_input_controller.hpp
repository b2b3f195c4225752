#pragma once
// Hand-held driving beside the keyboard: the on-screen drive pad (widgets/teleop/drive_pad.hpp)
// and the SDL2 gamepad (gamepad_teleop.hpp), both in a "Pad and gamepad" group at the bottom of
// the Drive tab, both driving the session's robot through SessionController::drive — the same
// path as the keyboard teleop, simulated or linked. Speed limits come from the robot profile.

#include <QObject>
#include <memory>

#include "app/gui/gamepad_source.hpp"

class QLabel;

namespace irgs::widgets {
class CommandPanel;
class DrivePad;
}  // namespace irgs::widgets

namespace irgs::gui {

class GamepadTeleop;
class SessionController;

class DriveInputController : public QObject {
  Q_OBJECT

 public:
  // `source`: the gamepad source (makeSdlGamepadSource() in the application, a fake in tests).
  DriveInputController(widgets::CommandPanel& panel, SessionController& session,
                       std::unique_ptr<GamepadSource> source, QObject* parent = nullptr);

  widgets::DrivePad& pad() const { return *pad_; }
  GamepadTeleop& gamepad() const { return *gamepad_; }
  QLabel& gamepadStatus() const { return *status_; }

 private:
  SessionController& session_;
  widgets::DrivePad* pad_ = nullptr;
  QLabel* status_ = nullptr;
  GamepadTeleop* gamepad_ = nullptr;
};

}  // namespace irgs::gui
