#include "comms/arcos/arcos_commands.hpp"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

#include "comms/arcos/arcos_packet.hpp"

namespace irgs::comms::arcos {

std::vector<std::uint8_t> commandPayload(std::uint8_t command) {
  return {command};
}

std::vector<std::uint8_t> commandPayload(std::uint8_t command, int argument) {
  if (argument < -kMaxIntArgument || argument > kMaxIntArgument) {
    throw std::invalid_argument("ARCOS int argument out of range (+-32767): " +
                                std::to_string(argument));
  }
  const auto magnitude = static_cast<unsigned>(std::abs(argument));
  return {command, argument < 0 ? kArgNegative : kArgPositive,
          static_cast<std::uint8_t>(magnitude & 0xFF), static_cast<std::uint8_t>(magnitude >> 8)};
}

std::vector<std::uint8_t> commandPayload(std::uint8_t command, std::string_view argument) {
  if (argument.size() > kMaxStringArgument) {
    throw std::invalid_argument("ARCOS string argument longer than 200 characters");
  }
  // Sized up front: GCC 12 misreports vector::insert of a char range as out of bounds.
  std::vector<std::uint8_t> payload(3 + argument.size());
  payload[0] = command;
  payload[1] = kArgString;
  payload[2] = static_cast<std::uint8_t>(argument.size());
  std::copy(argument.begin(), argument.end(), payload.begin() + 3);
  return payload;
}

std::vector<std::uint8_t> commandPacket(std::uint8_t command) {
  return framePacket(commandPayload(command));
}
std::vector<std::uint8_t> commandPacket(std::uint8_t command, int argument) {
  return framePacket(commandPayload(command, argument));
}
std::vector<std::uint8_t> commandPacket(std::uint8_t command, std::string_view argument) {
  return framePacket(commandPayload(command, argument));
}

int vel2Argument(int left_units, int right_units) {
  // -128 is excluded so that the 16-bit value never reaches -32768, beyond the int range.
  const auto to_byte = [](int units) {
    return static_cast<std::uint8_t>(static_cast<std::int8_t>(std::clamp(units, -127, 127)));
  };
  // ARIA's com2Bytes passes the two bytes to comInt(short): the argument is their signed 16-bit
  // value, so a negative left wheel travels as a negative int (sign byte 0x1b + magnitude).
  const auto bits = static_cast<std::uint16_t>(to_byte(left_units) << 8 | to_byte(right_units));
  return static_cast<std::int16_t>(bits);
}

WheelUnits splitVel2Argument(int argument) {
  const auto bits = static_cast<std::uint16_t>(argument);
  return {static_cast<std::int8_t>(bits >> 8), static_cast<std::int8_t>(bits & 0xFF)};
}

CommandParseResult parseCommand(std::span<const std::uint8_t> payload) {
  CommandParseResult result;
  if (payload.empty()) {
    result.error = "empty command packet";
    return result;
  }
  ParsedCommand parsed;
  parsed.command = payload[0];
  if (payload.size() == 1) {
    result.command = parsed;
    return result;
  }
  const std::uint8_t type = payload[1];
  if (type == kArgPositive || type == kArgNegative) {
    if (payload.size() != 4) {
      result.error = "command " + std::to_string(parsed.command) +
                     ": int argument needs 2 bytes, " + std::to_string(payload.size() - 2) +
                     " given";
      return result;
    }
    const int magnitude = payload[2] | payload[3] << 8;
    parsed.int_argument = type == kArgNegative ? -magnitude : magnitude;
  } else if (type == kArgString) {
    if (payload.size() < 3 || payload.size() - 3 < payload[2]) {
      result.error = "command " + std::to_string(parsed.command) + ": string argument truncated";
      return result;
    }
    parsed.string_argument.emplace(payload.begin() + 3, payload.begin() + 3 + payload[2]);
  } else {
    char hex[8];
    std::snprintf(hex, sizeof hex, "0x%02x", type);
    result.error = "command " + std::to_string(parsed.command) + ": unknown argument type " + hex;
    return result;
  }
  result.command = std::move(parsed);
  return result;
}

}  // namespace irgs::comms::arcos
