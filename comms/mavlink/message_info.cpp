#include "comms/mavlink/message_info.hpp"

#include <algorithm>

#include "comms/mavlink/messages.hpp"

namespace irgs::comms::mavlink {

static_assert(std::ranges::is_sorted(kGeneratedMessages, {}, &MessageInfo::id),
              "scripts/mavlink_gen.py must emit the table sorted by id");

std::span<const MessageInfo> generatedMessages() {
  return kGeneratedMessages;
}

std::optional<MessageInfo> findMessageInfo(std::uint32_t id, std::span<const MessageInfo> table) {
  const auto it = std::ranges::lower_bound(table, id, {}, &MessageInfo::id);
  if (it == table.end() || it->id != id) {
    return std::nullopt;
  }
  return *it;
}

}  // namespace irgs::comms::mavlink
