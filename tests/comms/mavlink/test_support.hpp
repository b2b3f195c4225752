#pragma once
// Helpers shared by the MAVLink codec tests.

#include <cstdint>
#include <string_view>
#include <vector>

namespace irgs::comms::mavlink::test {

inline std::vector<std::uint8_t> fromHex(std::string_view hex) {
  auto nibble = [](char c) { return static_cast<std::uint8_t>(c <= '9' ? c - '0' : c - 'a' + 10); };
  std::vector<std::uint8_t> bytes;
  for (std::size_t i = 0; i + 1 < hex.size(); i += 2) {
    bytes.push_back(static_cast<std::uint8_t>((nibble(hex[i]) << 4) | nibble(hex[i + 1])));
  }
  return bytes;
}

}  // namespace irgs::comms::mavlink::test
