#include "app/gui/gamepad_teleop.hpp"

#include <stdexcept>

namespace irgs::gui {

GamepadTeleop::GamepadTeleop(std::unique_ptr<GamepadSource> source, const MotionLimits& limits,
                             TeleopMappingConfig config, QObject* parent)
    : QObject(parent), source_(std::move(source)), limits_(limits), config_(config) {
  if (!source_)
    throw std::invalid_argument("GamepadTeleop: no source");
  validate(config_);
  timer_.setInterval(kPollInterval_ms);
  connect(&timer_, &QTimer::timeout, this, &GamepadTeleop::pollOnce);
}

void GamepadTeleop::pollOnce() {
  const std::optional<GamepadState> state = source_->poll();
  if (state.has_value() != connected_) {
    connected_ = state.has_value();
    emit connectionChanged(connected_, QString::fromStdString(source_->deviceName()));
  }
  const bool deadman =
      state && (config_.deadman_button < 0 || state->pressed(config_.deadman_button));
  if (!deadman) {
    if (driving_) {
      driving_ = false;
      last_ = {};
      emit released();
    }
    return;
  }
  // Without a dead-man button configured, a centred stick hands the command back (otherwise the
  // idle gamepad would hold the robot at zero against the keyboard and the pad).
  const VelocityCommand command = mapGamepad(*state, config_, limits_);
  if (config_.deadman_button < 0 && command == VelocityCommand{}) {
    if (driving_) {
      driving_ = false;
      last_ = {};
      emit released();
    }
    return;
  }
  if (!driving_ || !(command == last_)) {
    driving_ = true;
    last_ = command;
    emit commandChanged(command.linear_mps, command.angular_radps);
  }
}

QString GamepadTeleop::statusText() const {
  if (connected_)
    return tr("Gamepad: %1 (hold LB to drive, RB for full speed)")
        .arg(QString::fromStdString(source_->deviceName()));
  const std::string reason = source_->unavailableReason();
  if (!reason.empty())
    return tr("Gamepad: unavailable, %1").arg(QString::fromStdString(reason));
  return tr("Gamepad: none connected (plug one in at any time)");
}

}  // namespace irgs::gui
