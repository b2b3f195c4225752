#pragma once
// SHA-256 (FIPS 180-4), incremental. Used for MAVLink 2 message signing, which hashes the secret
// key followed by the frame, so the hash is fed in pieces without copying them together.

#include <array>
#include <cstdint>
#include <span>
#include <string_view>

namespace irgs::comms::mavlink {

using Sha256Digest = std::array<std::uint8_t, 32>;

class Sha256 {
 public:
  Sha256();
  void update(std::span<const std::uint8_t> bytes);
  void update(std::string_view text);
  // Pads, returns the digest and resets the object for a new message.
  Sha256Digest finish();

  static Sha256Digest hash(std::span<const std::uint8_t> bytes);

 private:
  void reset();
  void compress(const std::uint8_t* block);

  std::array<std::uint32_t, 8> state_{};
  std::array<std::uint8_t, 64> block_{};
  std::size_t block_used_ = 0;
  std::uint64_t total_bytes_ = 0;
};

}  // namespace irgs::comms::mavlink
