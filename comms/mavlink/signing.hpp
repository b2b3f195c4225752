#pragma once
// MAVLink 2 message signing (https://mavlink.io/en/guide/message_signing.html):
//   signature = first 6 bytes of SHA-256(secret_key[32] + header[10] + payload + crc[2]
//                                        + link_id[1] + timestamp[6])
// i.e. the key followed by every frame byte before the signature itself. The timestamp counts
// 10 us units since 2015-01-01T00:00:00Z in 48 bits and must increase per
// (link id, system id, component id) stream, which is what defeats replays.

#include <array>
#include <chrono>
#include <cstdint>
#include <span>
#include <string_view>

namespace irgs::comms::mavlink {

using SigningKey = std::array<std::uint8_t, 32>;
using Signature = std::array<std::uint8_t, 6>;

inline constexpr std::int64_t kSigningEpochUnixSeconds = 1420070400;  // 2015-01-01T00:00:00Z
inline constexpr std::uint64_t kSigningTimestampMask = (std::uint64_t{1} << 48) - 1;
inline constexpr std::uint64_t kSigningTicksPerSecond = 100000;  // 10 us units

// `frame_before_signature`: the frame from STX up to and including the 6 timestamp bytes.
Signature computeSignature(const SigningKey& key,
                           std::span<const std::uint8_t> frame_before_signature);

// Signing time of a wall-clock instant: 10 us units since 2015-01-01, 0 before that epoch.
std::uint64_t signingTimestampAt(std::chrono::system_clock::time_point time);

// A key from a passphrase, as MAVProxy/pymavlink derive it: SHA-256 of the UTF-8 text.
SigningKey signingKeyFromPassphrase(std::string_view passphrase);

}  // namespace irgs::comms::mavlink
