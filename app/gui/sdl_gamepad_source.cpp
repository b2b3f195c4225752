#include "app/gui/gamepad_source.hpp"

#include <algorithm>
#include <utility>

#if IRGS_HAVE_SDL2
#include <SDL.h>
#endif

namespace irgs::gui {

namespace {

#if IRGS_HAVE_SDL2

// SDL2's game-controller subsystem, polled (no SDL window, no SDL signal handlers). The first
// controller plugged in is used; when it is unplugged the next one present is opened.
class SdlGamepadSource : public GamepadSource {
 public:
  SdlGamepadSource() {
    SDL_SetHint(SDL_HINT_NO_SIGNAL_HANDLERS, "1");                // Ctrl+C stays Qt's
    SDL_SetHint(SDL_HINT_JOYSTICK_ALLOW_BACKGROUND_EVENTS, "1");  // the Qt window has focus
    if (SDL_InitSubSystem(SDL_INIT_GAMECONTROLLER) != 0)
      reason_ = std::string("SDL cannot start its game-controller support: ") + SDL_GetError();
    else
      started_ = true;
  }
  ~SdlGamepadSource() override {
    if (controller_ != nullptr)
      SDL_GameControllerClose(controller_);
    if (started_)
      SDL_QuitSubSystem(SDL_INIT_GAMECONTROLLER);
  }

  std::optional<GamepadState> poll() override {
    if (!started_)
      return std::nullopt;
    SDL_Event event;
    while (SDL_PollEvent(&event) != 0) {
      if (event.type == SDL_CONTROLLERDEVICEREMOVED && controller_ != nullptr &&
          event.cdevice.which == SDL_JoystickInstanceID(SDL_GameControllerGetJoystick(controller_)))
        closeController();
    }
    if (controller_ == nullptr)
      openFirst();
    if (controller_ == nullptr)
      return std::nullopt;
    if (SDL_GameControllerGetAttached(controller_) != SDL_TRUE) {
      closeController();
      return std::nullopt;
    }
    GamepadState state;
    for (int a = 0; a < GamepadState::kAxes && a < SDL_CONTROLLER_AXIS_MAX; ++a) {
      const Sint16 raw =
          SDL_GameControllerGetAxis(controller_, static_cast<SDL_GameControllerAxis>(a));
      state.axes[static_cast<std::size_t>(a)] = std::max(-1.0, raw / 32767.0);
    }
    for (int b = 0; b < SDL_CONTROLLER_BUTTON_MAX && b < 32; ++b)
      if (SDL_GameControllerGetButton(controller_, static_cast<SDL_GameControllerButton>(b)) != 0)
        state.buttons |= 1u << b;
    return state;
  }

  std::string deviceName() const override { return name_; }
  std::string unavailableReason() const override { return reason_; }

 private:
  void openFirst() {
    for (int i = 0; i < SDL_NumJoysticks(); ++i) {
      if (SDL_IsGameController(i) != SDL_TRUE)
        continue;
      controller_ = SDL_GameControllerOpen(i);
      if (controller_ != nullptr) {
        const char* name = SDL_GameControllerName(controller_);
        name_ = name != nullptr ? name : "gamepad";
        return;
      }
    }
  }
  void closeController() {
    SDL_GameControllerClose(controller_);
    controller_ = nullptr;
    name_.clear();
  }

  bool started_ = false;
  std::string reason_;
  SDL_GameController* controller_ = nullptr;
  std::string name_;
};

#else

class SdlGamepadSource : public GamepadSource {
 public:
  std::optional<GamepadState> poll() override { return std::nullopt; }
  std::string deviceName() const override { return {}; }
  std::string unavailableReason() const override {
    return "built without SDL2 (install libsdl2-dev and reconfigure)";
  }
};

#endif

}  // namespace

std::unique_ptr<GamepadSource> makeSdlGamepadSource() {
  return std::make_unique<SdlGamepadSource>();
}

}  // namespace irgs::gui
