#pragma once
// MAVLink frame layout (https://mavlink.io/en/guide/serialization.html) and the decoded frame.
//
// v2: STX(0xFD) len incompat_flags compat_flags seq sysid compid msgid[3 LE] payload[len]
//     crc[2 LE] [signature: link_id timestamp[6 LE] signature[6]]   (signed if incompat & 0x01)
// v1: STX(0xFE) len seq sysid compid msgid payload[len] crc[2 LE]

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

namespace irgs::comms::mavlink {

inline constexpr std::uint8_t kStxV2 = 0xFD;
inline constexpr std::uint8_t kStxV1 = 0xFE;
inline constexpr std::size_t kHeaderLengthV2 = 10;  // including STX
inline constexpr std::size_t kHeaderLengthV1 = 6;   // including STX
inline constexpr std::size_t kChecksumLength = 2;
inline constexpr std::size_t kSignatureLength = 13;  // link id, timestamp, 6-byte signature
inline constexpr std::size_t kMaxPayloadLength = 255;
inline constexpr std::size_t kMaxFrameLength =
    kHeaderLengthV2 + kMaxPayloadLength + kChecksumLength + kSignatureLength;
inline constexpr std::uint8_t kIncompatFlagSigned = 0x01;
inline constexpr std::uint8_t kKnownIncompatFlags = kIncompatFlagSigned;

enum class ProtocolVersion : std::uint8_t { kV1 = 1, kV2 = 2 };

// One frame that passed the checksum (and the signature checks the decoder was asked for).
struct Frame {
  ProtocolVersion version = ProtocolVersion::kV2;
  std::uint8_t incompat_flags = 0;
  std::uint8_t compat_flags = 0;
  std::uint8_t sequence = 0;
  std::uint8_t system_id = 0;
  std::uint8_t component_id = 0;
  std::uint32_t message_id = 0;
  std::uint8_t payload_length = 0;  // bytes on the wire, after trailing-zero truncation
  // Wire-order payload; bytes from payload_length up to the message's maximum length are zero
  // (re-extension), so it can be unpacked as the full message.
  std::array<std::uint8_t, kMaxPayloadLength> payload{};
  bool is_signed = false;
  bool signature_verified = false;        // false when signed but the decoder has no key
  std::uint8_t link_id = 0;               // signed frames only
  std::uint64_t signature_timestamp = 0;  // signed frames only, 10 us units since 2015-01-01

  std::span<const std::uint8_t> payloadBytes() const { return {payload.data(), payload_length}; }

  // The typed message if this frame carries M.
  template <class M>
  std::optional<M> as() const {
    if (message_id != M::kId) {
      return std::nullopt;
    }
    return M::unpack(payloadBytes());
  }
};

}  // namespace irgs::comms::mavlink
