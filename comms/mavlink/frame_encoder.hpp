#pragma once
// Building MAVLink frames for sending. Pure: the caller supplies the signing time (see
// signingTimestampAt) so encoding is deterministic and testable.

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "comms/mavlink/frame.hpp"
#include "comms/mavlink/message_info.hpp"
#include "comms/mavlink/signing.hpp"

namespace irgs::comms::mavlink {

// A frame ready to write: fixed storage, no allocation.
struct EncodedFrame {
  std::array<std::uint8_t, kMaxFrameLength> bytes{};
  std::size_t size = 0;
  std::span<const std::uint8_t> view() const { return {bytes.data(), size}; }
};

struct FrameHeaderFields {
  std::uint8_t sequence = 0;
  std::uint8_t system_id = 0;
  std::uint8_t component_id = 0;
  std::uint8_t compat_flags = 0;
};

struct SignatureFields {
  SigningKey key{};
  std::uint8_t link_id = 0;
  std::uint64_t timestamp = 0;  // 10 us units since 2015-01-01, 48 bits
};

// Encodes one MAVLink 2 frame. `payload` is the untrimmed wire-order payload (at most
// info.max_length bytes, else std::invalid_argument); trailing zero bytes are dropped, keeping at
// least one byte as the spec requires. Signed when `signature` is given. Returns the frame size.
std::size_t encodeFrame(std::span<std::uint8_t, kMaxFrameLength> out, const MessageInfo& info,
                        std::span<const std::uint8_t> payload, const FrameHeaderFields& header,
                        const SignatureFields* signature = nullptr);

// Encodes a MAVLink 1 frame (legacy peers and tests; this project sends v2). Only ids < 256 and
// no extensions: the payload is cut to info.min_length. Throws std::invalid_argument otherwise.
std::size_t encodeFrameV1(std::span<std::uint8_t, kMaxFrameLength> out, const MessageInfo& info,
                          std::span<const std::uint8_t> payload, const FrameHeaderFields& header);

// One sender (system id, component id): numbers its frames 0, 1, ... 255, 0, ... and signs them
// when a key is set, keeping the signing timestamp strictly increasing even when the caller's
// clock stalls or steps back.
class FrameEncoder {
 public:
  FrameEncoder(std::uint8_t system_id, std::uint8_t component_id);

  void enableSigning(const SigningKey& key, std::uint8_t link_id);
  void disableSigning();
  bool signing() const { return key_.has_value(); }

  // `signing_time`: now, as signingTimestampAt(system_clock::now()); ignored when not signing.
  template <class M>
  EncodedFrame encode(const M& message, std::uint64_t signing_time = 0) {
    std::array<std::uint8_t, M::kMaxLength> payload{};
    message.pack(payload);
    return encodePayload(messageInfoOf<M>(), payload, signing_time);
  }

  EncodedFrame encodePayload(const MessageInfo& info, std::span<const std::uint8_t> payload,
                             std::uint64_t signing_time = 0);

  std::uint8_t nextSequence() const { return sequence_; }
  std::uint8_t systemId() const { return system_id_; }
  std::uint8_t componentId() const { return component_id_; }
  std::uint64_t lastSigningTimestamp() const { return last_timestamp_; }

 private:
  std::uint8_t system_id_;
  std::uint8_t component_id_;
  std::uint8_t sequence_ = 0;
  std::optional<SigningKey> key_;
  std::uint8_t link_id_ = 0;
  std::uint64_t last_timestamp_ = 0;
};

}  // namespace irgs::comms::mavlink
