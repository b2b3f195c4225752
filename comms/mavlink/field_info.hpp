#pragma once
// The numeric fields of a MAVLink message as data: a table per message, generated into
// messages.hpp by scripts/mavlink_gen.py, so code that shows or records "any field of any
// message" (the plots' field browser) needs no hand-written code per message.
//
// A table entry is one numeric value: a scalar field, or one element of an array field (each
// element has its own entry). char[] text is not numeric and has no entry. The offset is into
// the wire-order payload of a decoded Frame, whose bytes beyond the received length are zero
// (MAVLink 2 re-extension): a trimmed field reads as zero, as the typed unpack() gives it.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

namespace irgs::comms::mavlink {

struct Frame;

enum class FieldType : std::uint8_t {
  kUint8,
  kInt8,
  kUint16,
  kInt16,
  kUint32,
  kInt32,
  kUint64,
  kInt64,
  kFloat,
  kDouble,
};

constexpr std::size_t sizeOf(FieldType type) {
  switch (type) {
    case FieldType::kUint8:
    case FieldType::kInt8:
      return 1;
    case FieldType::kUint16:
    case FieldType::kInt16:
      return 2;
    case FieldType::kUint32:
    case FieldType::kInt32:
    case FieldType::kFloat:
      return 4;
    case FieldType::kUint64:
    case FieldType::kInt64:
    case FieldType::kDouble:
      return 8;
  }
  return 0;
}

std::string_view toString(FieldType type);  // "uint8_t", ..., "double"

struct FieldInfo {
  std::string_view name;  // the XML field name ("range" for every element of range[12])
  std::string_view unit;  // the XML units attribute ("m", "rad/s", "cdegC"); empty when none
  FieldType type = FieldType::kUint8;
  std::uint8_t offset = 0;        // byte offset of this value in the wire-order payload
  std::int16_t array_index = -1;  // element of an array field; -1 for a scalar
  // XML instance="true": the value tells apart streams of one message id (DISTANCE_SENSOR's
  // sensor id), so a consumer keeps one series per instance.
  bool instance = false;
  bool extension = false;  // a MAVLink 2 extension field (absent from MAVLink 1 senders)
};

// One message's table (what the generator emits per message, gathered for lookup by id).
struct MessageFields {
  std::uint32_t id = 0;
  std::string_view name;
  std::span<const FieldInfo> fields;
};

template <class M>
constexpr MessageFields messageFieldsOf() {
  return {M::kId, M::kName, M::kFields};
}

// The field tables of every message generated into messages.hpp, sorted by id.
std::span<const MessageFields> generatedMessageFields();
// Null for an id without a generated table.
const MessageFields* findMessageFields(std::uint32_t id);

// The value at `field` in a wire-order `payload` (bytes beyond payload.size() read as zero),
// as double; 64-bit integers beyond 2^53 round to the nearest double.
double readField(const FieldInfo& field, std::span<const std::uint8_t> payload);
// The same from a decoded frame (its payload array includes the re-extended zero bytes).
double readField(const FieldInfo& field, const Frame& frame);

// Index in `message.fields` of its instance field; nullopt when it has none.
std::optional<std::size_t> instanceField(const MessageFields& message);
// The robot-clock time stamp of a message that carries one, in seconds: time_boot_ms (ms since
// boot) or time_usec (us; the IRGS firmware sends time since boot there, docs/protocol.md).
// nullopt for messages without either field.
std::optional<double> timeStamp_s(const MessageFields& message, const Frame& frame);

}  // namespace irgs::comms::mavlink
