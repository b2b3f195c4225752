#include "comms/mavlink/field_info.hpp"

#include <algorithm>

#include "comms/mavlink/frame.hpp"
#include "comms/mavlink/messages.hpp"
#include "comms/mavlink/wire.hpp"

namespace irgs::comms::mavlink {
namespace {

static_assert(std::ranges::is_sorted(kGeneratedMessageFields, {}, &MessageFields::id),
              "scripts/mavlink_gen.py must emit the field tables sorted by id");

template <class T>
double readAs(std::span<const std::uint8_t> payload, std::size_t offset) {
  T value{};
  wire::get(payload, offset, value);
  return static_cast<double>(value);
}

}  // namespace

std::string_view toString(FieldType type) {
  switch (type) {
    case FieldType::kUint8:
      return "uint8_t";
    case FieldType::kInt8:
      return "int8_t";
    case FieldType::kUint16:
      return "uint16_t";
    case FieldType::kInt16:
      return "int16_t";
    case FieldType::kUint32:
      return "uint32_t";
    case FieldType::kInt32:
      return "int32_t";
    case FieldType::kUint64:
      return "uint64_t";
    case FieldType::kInt64:
      return "int64_t";
    case FieldType::kFloat:
      return "float";
    case FieldType::kDouble:
      return "double";
  }
  return "?";
}

std::span<const MessageFields> generatedMessageFields() {
  return kGeneratedMessageFields;
}

const MessageFields* findMessageFields(std::uint32_t id) {
  const auto it = std::ranges::lower_bound(kGeneratedMessageFields, id, {}, &MessageFields::id);
  return it == kGeneratedMessageFields.end() || it->id != id ? nullptr : &*it;
}

double readField(const FieldInfo& field, std::span<const std::uint8_t> payload) {
  switch (field.type) {
    case FieldType::kUint8:
      return readAs<std::uint8_t>(payload, field.offset);
    case FieldType::kInt8:
      return readAs<std::int8_t>(payload, field.offset);
    case FieldType::kUint16:
      return readAs<std::uint16_t>(payload, field.offset);
    case FieldType::kInt16:
      return readAs<std::int16_t>(payload, field.offset);
    case FieldType::kUint32:
      return readAs<std::uint32_t>(payload, field.offset);
    case FieldType::kInt32:
      return readAs<std::int32_t>(payload, field.offset);
    case FieldType::kUint64:
      return readAs<std::uint64_t>(payload, field.offset);
    case FieldType::kInt64:
      return readAs<std::int64_t>(payload, field.offset);
    case FieldType::kFloat:
      return readAs<float>(payload, field.offset);
    case FieldType::kDouble:
      return readAs<double>(payload, field.offset);
  }
  return 0.0;
}

double readField(const FieldInfo& field, const Frame& frame) {
  return readField(field, std::span<const std::uint8_t>(frame.payload));
}

std::optional<std::size_t> instanceField(const MessageFields& message) {
  for (std::size_t i = 0; i < message.fields.size(); ++i) {
    if (message.fields[i].instance)
      return i;
  }
  return std::nullopt;
}

std::optional<double> timeStamp_s(const MessageFields& message, const Frame& frame) {
  for (const FieldInfo& field : message.fields) {
    if (field.array_index >= 0)
      continue;
    if (field.name == "time_boot_ms")
      return readField(field, frame) * 1e-3;
    if (field.name == "time_usec")
      return readField(field, frame) * 1e-6;
  }
  return std::nullopt;
}

}  // namespace irgs::comms::mavlink
