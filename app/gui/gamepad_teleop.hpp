#pragma once
// Gamepad driving: polls a GamepadSource from a timer (50 Hz), maps each reading through the
// pure teleop mapping (core/robot/teleop_mapping.hpp: axes, deadband, expo, dead-man, the
// profile's speed limits) and emits the command while the dead-man is held. Releasing the
// dead-man, or the gamepad going away (unplugged, battery), emits released() once: stop.
// With no gamepad, or the dead-man never pressed, it emits nothing, so the keyboard, the drive
// pad and behaviours drive undisturbed.

#include <QObject>
#include <QString>
#include <QTimer>
#include <memory>

#include "app/gui/gamepad_source.hpp"
#include "core/robot/robot_profile.hpp"
#include "core/robot/teleop_mapping.hpp"

namespace irgs::gui {

class GamepadTeleop : public QObject {
  Q_OBJECT

 public:
  static constexpr int kPollInterval_ms = 20;

  // Throws std::invalid_argument for a null source or an invalid mapping.
  GamepadTeleop(std::unique_ptr<GamepadSource> source, const MotionLimits& limits,
                TeleopMappingConfig config = {}, QObject* parent = nullptr);

  void setLimits(const MotionLimits& limits) { limits_ = limits; }
  void start() { timer_.start(); }
  void stop() { timer_.stop(); }
  // One poll (the timer calls this; tests call it directly).
  void pollOnce();

  bool connected() const { return connected_; }
  bool driving() const { return driving_; }
  // A line for the status label: the device, or why there is none.
  QString statusText() const;

 signals:
  void commandChanged(double linear_mps, double angular_radps);
  void released();
  void connectionChanged(bool connected, const QString& device);

 private:
  std::unique_ptr<GamepadSource> source_;
  MotionLimits limits_;
  TeleopMappingConfig config_;
  QTimer timer_;
  bool connected_ = false;
  bool driving_ = false;  // the dead-man is held: the gamepad owns the command
  VelocityCommand last_;
};

}  // namespace irgs::gui
