#pragma once
// What the framing layer needs to know about a message id: its CRC_EXTRA seed and the payload
// lengths a sender may put on the wire.

#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

namespace irgs::comms::mavlink {

struct MessageInfo {
  std::uint32_t id = 0;
  std::uint8_t crc_extra = 0;
  std::uint8_t min_length = 0;  // base fields: the MAVLink 1 payload length
  std::uint8_t max_length = 0;  // base plus extension fields: the untrimmed MAVLink 2 length
  std::string_view name;
  friend bool operator==(const MessageInfo&, const MessageInfo&) = default;
};

template <class M>
constexpr MessageInfo messageInfoOf() {
  return {M::kId, M::kCrcExtra, M::kMinLength, M::kMaxLength, M::kName};
}

// All messages generated into messages.hpp (common subset plus the IRGS dialect), sorted by id.
std::span<const MessageInfo> generatedMessages();

// Binary search in a table sorted by id; nullopt for an id the table does not know.
std::optional<MessageInfo> findMessageInfo(
    std::uint32_t id, std::span<const MessageInfo> table = generatedMessages());

}  // namespace irgs::comms::mavlink
