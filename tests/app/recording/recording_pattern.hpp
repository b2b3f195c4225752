#pragma once
// The frame contents of the SIGKILL test: frame i is 1..40 bytes derived from i, so a reader can
// tell every frame's index and integrity.

#include <cstdint>
#include <vector>

namespace irgs::recording::testing {

inline std::vector<std::uint8_t> pattern(std::size_t index) {
  std::vector<std::uint8_t> bytes(1 + index % 40);
  for (std::size_t i = 0; i < bytes.size(); ++i)
    bytes[i] = static_cast<std::uint8_t>((index * 31 + i * 7) & 0xff);
  return bytes;
}

}  // namespace irgs::recording::testing
