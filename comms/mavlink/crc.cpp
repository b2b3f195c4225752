#include "comms/mavlink/crc.hpp"

namespace irgs::comms::mavlink {

std::uint16_t crcAccumulate(std::span<const std::uint8_t> bytes, std::uint16_t crc) {
  for (const std::uint8_t b : bytes) {
    crc = crcAccumulate(b, crc);
  }
  return crc;
}

std::uint16_t crcAccumulate(std::string_view text, std::uint16_t crc) {
  for (const char c : text) {
    crc = crcAccumulate(static_cast<std::uint8_t>(c), crc);
  }
  return crc;
}

}  // namespace irgs::comms::mavlink
