#include "app/gui/drive_input_controller.hpp"

#include <QGroupBox>
#include <QLabel>
#include <QVBoxLayout>

#include "app/gui/gamepad_teleop.hpp"
#include "app/gui/session_controller.hpp"
#include "widgets/command/command_panel.hpp"
#include "widgets/teleop/drive_pad.hpp"

namespace irgs::gui {

DriveInputController::DriveInputController(widgets::CommandPanel& panel, SessionController& session,
                                           std::unique_ptr<GamepadSource> source, QObject* parent)
    : QObject(parent), session_(session) {
  const MotionLimits& limits = session_.profile().limits;
  auto* group = new QGroupBox(tr("Pad and gamepad"));
  group->setObjectName(QStringLiteral("drivePadGroup"));
  auto* column = new QVBoxLayout(group);
  pad_ = new widgets::DrivePad(group);
  pad_->setMaxSpeeds(limits.max_speed_mps, limits.max_turn_rate_radps);
  pad_->setMinimumHeight(140);
  column->addWidget(pad_);
  status_ = new QLabel(group);
  status_->setObjectName(QStringLiteral("gamepadStatus"));
  status_->setWordWrap(true);
  column->addWidget(status_);
  panel.addSection(group);

  gamepad_ = new GamepadTeleop(std::move(source), limits, {}, this);
  status_->setText(gamepad_->statusText());

  connect(pad_, &widgets::DrivePad::commandChanged, &session_, &SessionController::drive);
  connect(pad_, &widgets::DrivePad::released, &session_, &SessionController::stopRobot);
  connect(gamepad_, &GamepadTeleop::commandChanged, &session_, &SessionController::drive);
  connect(gamepad_, &GamepadTeleop::released, &session_, &SessionController::stopRobot);
  connect(gamepad_, &GamepadTeleop::connectionChanged, this,
          [this](bool connected, const QString& device) {
            status_->setText(gamepad_->statusText());
            session_.report(EventLevel::kInfo, connected ? tr("Gamepad connected: %1").arg(device)
                                                         : tr("Gamepad disconnected"));
          });
  gamepad_->start();
}

}  // namespace irgs::gui
