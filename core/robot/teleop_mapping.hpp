#pragma once
// Hand-held driving input -> velocity command, pure: the gamepad (SDL2 in app/gui) and the
// on-screen drive pad (widgets/teleop) both map through here, so deadband, expo, dead-man and
// the profile's speed limits behave the same whatever the device.
//
// Axes are normalised to [-1, 1] with SDL's conventions: stick right = +x, stick down = +y.
// The command follows our frames: forward = +v, counter-clockwise (left) = +omega, so pushing a
// stick up drives forward and pushing it right turns clockwise.

#include <array>
#include <cstdint>
#include <optional>

#include "core/robot/robot_profile.hpp"
#include "core/robot/telemetry.hpp"

namespace irgs {

// One reading of a gamepad. Missing axes read 0, missing buttons released.
struct GamepadState {
  static constexpr int kAxes = 6;  // SDL_GameController: LX, LY, RX, RY, LT, RT
  std::array<double, kAxes> axes{};
  std::uint32_t buttons = 0;  // bit i = SDL_GameController button i held
  bool pressed(int button) const {
    return button >= 0 && button < 32 && ((buttons >> button) & 1u) != 0;
  }
};

struct TeleopAxisConfig {
  int axis = 0;         // index into GamepadState::axes
  bool invert = false;  // negate the raw axis before the mapping
};

struct TeleopMappingConfig {
  TeleopAxisConfig linear{1, true};   // left stick vertical: up (-y) is forward
  TeleopAxisConfig angular{2, true};  // right stick horizontal: right (+x) turns clockwise
  double deadband = 0.12;             // |axis| below this is 0; the rest is rescaled to 0..1
  double expo = 0.4;                  // 0: linear; 1: cubic (fine control near the centre)
  int deadman_button = 9;             // SDL_CONTROLLER_BUTTON_LEFTSHOULDER; -1: no dead-man
  int turbo_button = 10;              // RIGHTSHOULDER: full profile speed; -1: none
  double normal_fraction = 0.5;       // of the profile's limits without turbo
};

// Throws std::invalid_argument for a deadband outside [0, 1), expo outside [0, 1], a
// normal_fraction outside (0, 1], or an axis index outside the state.
void validate(const TeleopMappingConfig& config);

// The deadband and expo of one normalised axis value (clamped to [-1, 1]; NaN reads 0).
double shapeAxis(double value, double deadband, double expo);

// The command for one reading; zero when the dead-man is configured and not held. Speeds are
// `limits`' maxima times normal_fraction (or 1 with turbo), and never exceed the limits.
VelocityCommand mapGamepad(const GamepadState& state, const TeleopMappingConfig& config,
                           const MotionLimits& limits);

// A stick position (x right, y down, both in [-1, 1]) to a command at the given maximum speeds,
// with the same shaping: the on-screen pad.
VelocityCommand mapStick(double x, double y, double deadband, double expo, double max_linear_mps,
                         double max_angular_radps);

}  // namespace irgs
