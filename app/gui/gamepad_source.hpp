#pragma once
// Where gamepad readings come from. The real one polls SDL2's game-controller API
// (sdl_gamepad_source.cpp); tests use a fake. Kept out of widgets/ (Qt only) and core (no
// devices): the GUI polls it from a timer (GamepadTeleop).

#include <memory>
#include <optional>
#include <string>

#include "core/robot/teleop_mapping.hpp"

namespace irgs::gui {

class GamepadSource {
 public:
  virtual ~GamepadSource() = default;
  // Handles hot-plug and returns the newest reading of the open gamepad, or nothing when none
  // is connected. Never blocks.
  virtual std::optional<GamepadState> poll() = 0;
  // The open gamepad's name, empty when none.
  virtual std::string deviceName() const = 0;
  // Why gamepads cannot be used at all (SDL could not start), empty when they can.
  virtual std::string unavailableReason() const = 0;
};

// The SDL2 game-controller source (any gamepad SDL knows a mapping for: Xbox, PlayStation,
// Switch Pro, most USB pads). Without SDL2 at build time, one that reports itself unavailable.
std::unique_ptr<GamepadSource> makeSdlGamepadSource();

}  // namespace irgs::gui
