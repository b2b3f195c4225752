#pragma once
// X.25 CRC-16 as used by MAVLink (CRC-16/MCRF4XX: poly 0x1021 reflected, init 0xFFFF, no final
// xor). The checksum of a frame covers the header without STX, the payload as sent and, last,
// the message's CRC_EXTRA byte, which binds the frame to the sender's field layout.

#include <cstdint>
#include <span>
#include <string_view>

namespace irgs::comms::mavlink {

inline constexpr std::uint16_t kCrcInit = 0xFFFF;

// Folds one byte into a running CRC (the accumulate step of the MAVLink reference code).
constexpr std::uint16_t crcAccumulate(std::uint8_t byte, std::uint16_t crc) {
  auto tmp = static_cast<std::uint8_t>(byte ^ static_cast<std::uint8_t>(crc & 0xFF));
  tmp = static_cast<std::uint8_t>(tmp ^ static_cast<std::uint8_t>(tmp << 4));
  return static_cast<std::uint16_t>((crc >> 8) ^ (tmp << 8) ^ (tmp << 3) ^ (tmp >> 4));
}

std::uint16_t crcAccumulate(std::span<const std::uint8_t> bytes, std::uint16_t crc = kCrcInit);
std::uint16_t crcAccumulate(std::string_view text, std::uint16_t crc = kCrcInit);

// The 8-bit seed of a message from its CRC over the layout string: (crc & 0xFF) ^ (crc >> 8).
constexpr std::uint8_t foldCrcExtra(std::uint16_t crc) {
  return static_cast<std::uint8_t>((crc & 0xFF) ^ (crc >> 8));
}

}  // namespace irgs::comms::mavlink
