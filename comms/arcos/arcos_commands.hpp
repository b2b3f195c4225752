#pragma once
// ARCOS client commands (Pioneer 3 Operations Manual, "ARCOS client commands"; ARIA
// ArCommands): the payload is the command number, then optionally one argument:
//
//   int     0x3B (positive) or 0x1B (negative), then the magnitude as 2 bytes little-endian
//   string  0x2B, a length byte, then that many characters (no terminator)
//
// e.g. VEL 200 -> payload 0b 3b c8 00 -> packet fa fb 06 0b 3b c8 00 d3 3b.

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace irgs::comms::arcos {

// Command numbers used by IRGS (the full ARCOS list is longer; unknown numbers are still parsed
// and reported by number).
enum class Command : std::uint8_t {
  kSync0 = 0,  // also PULSE once connected: resets the server watchdog
  kSync1 = 1,  // also OPEN once synchronised: starts the servers and the SIP stream
  kSync2 = 2,  // also CLOSE once open
  kPolling = 3,
  kEnable = 4,  // 1 enables the motors, 0 disables them
  kSetA = 5,
  kSetV = 6,
  kSetO = 7,  // resets the odometry origin
  kMove = 8,  // mm, relative
  kRotate = 9,
  kSetRv = 10,
  kVel = 11,   // mm/s
  kHead = 12,  // absolute heading, degrees
  kDHead = 13,
  kConfig = 18,  // asks for one CONFIGpac
  kRVel = 21,    // deg/s
  kSonar = 28,   // 1 enables, 0 disables all sonar arrays
  kStop = 29,
  kVel2 = 32,  // independent wheel velocities (see vel2Argument)
  kEStop = 55,
};
inline constexpr std::uint8_t kPulse = 0;
inline constexpr std::uint8_t kOpen = 1;
inline constexpr std::uint8_t kClose = 2;

inline constexpr std::uint8_t kArgPositive = 0x3B;
inline constexpr std::uint8_t kArgNegative = 0x1B;
inline constexpr std::uint8_t kArgString = 0x2B;
inline constexpr int kMaxIntArgument = 32767;
inline constexpr std::size_t kMaxStringArgument = 200;

// Payloads (frame them with framePacket). Throw std::invalid_argument for an int argument
// outside +-32767 or a string longer than 200 characters: callers clamp physical values first.
std::vector<std::uint8_t> commandPayload(std::uint8_t command);
std::vector<std::uint8_t> commandPayload(std::uint8_t command, int argument);
std::vector<std::uint8_t> commandPayload(std::uint8_t command, std::string_view argument);
inline std::vector<std::uint8_t> commandPayload(Command command) {
  return commandPayload(static_cast<std::uint8_t>(command));
}
inline std::vector<std::uint8_t> commandPayload(Command command, int argument) {
  return commandPayload(static_cast<std::uint8_t>(command), argument);
}

// Complete packets, ready to write.
std::vector<std::uint8_t> commandPacket(std::uint8_t command);
std::vector<std::uint8_t> commandPacket(std::uint8_t command, int argument);
std::vector<std::uint8_t> commandPacket(std::uint8_t command, std::string_view argument);
inline std::vector<std::uint8_t> commandPacket(Command command) {
  return commandPacket(static_cast<std::uint8_t>(command));
}
inline std::vector<std::uint8_t> commandPacket(Command command, int argument) {
  return commandPacket(static_cast<std::uint8_t>(command), argument);
}

// VEL2's argument: the low byte is the right wheel, the high byte the left wheel, each a signed
// byte in units of Vel2Divisor mm/s (20 mm/s on a P3-DX). Values are clamped to -127..127.
// The result is the two bytes read as a signed 16-bit value, ready for commandPacket(int).
int vel2Argument(int left_units, int right_units);
struct WheelUnits {
  int left = 0;
  int right = 0;
};
WheelUnits splitVel2Argument(int argument);

// A command received by a server (the virtual Pioneer).
struct ParsedCommand {
  std::uint8_t command = 0;
  std::optional<int> int_argument;
  std::optional<std::string> string_argument;
};
struct CommandParseResult {
  std::optional<ParsedCommand> command;
  std::string error;  // set when command is empty: why the payload is not a valid command
};
CommandParseResult parseCommand(std::span<const std::uint8_t> payload);

}  // namespace irgs::comms::arcos
