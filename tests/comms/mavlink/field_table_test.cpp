// The generated field tables: for every message, every table entry set through the typed struct
// (setField, by member) survives pack, encode and decode and reads back by the table (offset
// and type) as the value set; the entries cover the payload without overlapping; trimmed
// extensions read as zero; instance and time-stamp fields are found.

#include <gtest/gtest.h>

#include <limits>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "comms/mavlink/field_info.hpp"
#include "comms/mavlink/frame_decoder.hpp"
#include "comms/mavlink/frame_encoder.hpp"
#include "comms/mavlink/messages.hpp"

namespace irgs::comms::mavlink {
namespace {

// A value for entry `i` that is exact in the field's type and differs from its neighbours',
// so an entry reading the bytes of another one is caught. Signed types get negative values.
double distinctValue(const FieldInfo& field, std::size_t i) {
  const double k = static_cast<double>(i + 1);
  switch (field.type) {
    case FieldType::kUint8:
      return 100.0 + k;  // < 256 for up to 155 entries
    case FieldType::kInt8:
      return -(k + 1.0);
    case FieldType::kUint16:
      return 40000.0 + k;
    case FieldType::kInt16:
      return -20000.0 - k;
    case FieldType::kUint32:
      return 3.0e9 + k;
    case FieldType::kInt32:
      return -2.0e9 - k;
    case FieldType::kUint64:
      return 1.0e15 + k;  // exact in a double
    case FieldType::kInt64:
      return -1.0e15 - k;
    case FieldType::kFloat:
      return 0.25 * k - 1000.5;  // exact in a float
    case FieldType::kDouble:
      return 1.0 / 3.0 + k;
  }
  return 0.0;
}

// char[] text bytes per message (not in the tables); every other payload byte is a table entry's.
const std::map<std::string, std::size_t> kTextBytes = {
    {"STATUSTEXT", 50}, {"PARAM_VALUE", 16}, {"PARAM_SET", 16}, {"PARAM_REQUEST_READ", 16}};

template <class M>
void checkTable() {
  SCOPED_TRACE(std::string(M::kName));
  const std::span<const FieldInfo> fields = M::kFields;
  ASSERT_FALSE(fields.empty());

  // Entries cover the payload once: no byte belongs to two, and only text is left over.
  std::vector<int> owner(M::kMaxLength, -1);
  for (std::size_t i = 0; i < fields.size(); ++i) {
    const FieldInfo& f = fields[i];
    ASSERT_LE(f.offset + sizeOf(f.type), M::kMaxLength) << f.name;
    for (std::size_t b = f.offset; b < f.offset + sizeOf(f.type); ++b) {
      EXPECT_EQ(owner[b], -1) << f.name << " overlaps entry " << owner[b];
      owner[b] = static_cast<int>(i);
    }
    EXPECT_EQ(f.extension, f.offset >= M::kMinLength) << f.name;
  }
  const auto text = kTextBytes.find(std::string(M::kName));
  const std::size_t text_bytes = text == kTextBytes.end() ? 0 : text->second;
  EXPECT_EQ(static_cast<std::size_t>(std::count(owner.begin(), owner.end(), -1)), text_bytes);

  // Set every entry through the struct, send it, read every entry back through the table.
  M message;
  for (std::size_t i = 0; i < fields.size(); ++i)
    ASSERT_TRUE(message.setField(i, distinctValue(fields[i], i)));
  EXPECT_FALSE(message.setField(fields.size(), 1.0));
  FrameEncoder encoder(7, 1);
  FrameDecoder decoder;
  const DecodeResult result = decoder.feed(encoder.encode(message).view());
  ASSERT_EQ(result.frames.size(), 1u);
  const Frame& frame = result.frames[0];
  const MessageFields* table = findMessageFields(frame.message_id);
  ASSERT_NE(table, nullptr);
  EXPECT_EQ(table->name, M::kName);
  ASSERT_EQ(table->fields.size(), fields.size());
  for (std::size_t i = 0; i < fields.size(); ++i) {
    const FieldInfo& f = table->fields[i];
    const double expected = distinctValue(f, i);
    if (f.type == FieldType::kFloat)
      EXPECT_EQ(readField(f, frame), static_cast<double>(static_cast<float>(expected))) << f.name;
    else
      EXPECT_EQ(readField(f, frame), expected) << f.name << "[" << f.array_index << "]";
  }

  // A sender without extensions (MAVLink 1 era): the extension entries read as zero.
  M base_only;
  for (std::size_t i = 0; i < fields.size(); ++i) {
    if (!fields[i].extension)
      base_only.setField(i, distinctValue(fields[i], i));
  }
  std::array<std::uint8_t, M::kMaxLength> bytes{};
  base_only.pack(bytes);
  const std::span<const std::uint8_t> trimmed(bytes.data(), M::kMinLength);
  for (std::size_t i = 0; i < fields.size(); ++i) {
    if (fields[i].extension)
      EXPECT_EQ(readField(fields[i], trimmed), 0.0) << fields[i].name;
    else
      EXPECT_NE(readField(fields[i], trimmed), 0.0) << fields[i].name;
  }
}

template <class... Ms>
void checkAll(std::tuple<Ms...>*) {
  (checkTable<Ms>(), ...);
}

TEST(MavlinkFieldTables, EveryMessagesFieldsRoundTripThroughTheirTable) {
  checkAll(static_cast<GeneratedMessageTypes*>(nullptr));
  EXPECT_EQ(generatedMessageFields().size(), std::tuple_size_v<GeneratedMessageTypes>);
  EXPECT_EQ(findMessageFields(4242), nullptr);
}

TEST(MavlinkFieldTables, ArraysHaveOneEntryPerElementWithUnitsFromTheXml) {
  const std::span<const FieldInfo> f = IrgsSonarScan::kFields;
  ASSERT_EQ(f.size(), 15u);  // time_boot_ms, count, fired, range[12]
  EXPECT_EQ(f[0].name, "time_boot_ms");
  EXPECT_EQ(f[0].unit, "ms");
  EXPECT_EQ(f[3].name, "range");
  EXPECT_EQ(f[3].array_index, 0);
  EXPECT_EQ(f[14].array_index, 11);
  EXPECT_EQ(f[14].unit, "mm");
  EXPECT_EQ(f[14].type, FieldType::kUint16);
  EXPECT_EQ(toString(f[14].type), "uint16_t");
  // Text is not numeric: STATUSTEXT keeps severity, id and chunk_seq only.
  for (const FieldInfo& s : Statustext::kFields)
    EXPECT_NE(s.name, "text");
  EXPECT_EQ(Statustext::kFields.size(), 3u);
}

TEST(MavlinkFieldTables, InstanceAndTimeStampFieldsAreFound) {
  const MessageFields* distance = findMessageFields(DistanceSensor::kId);
  ASSERT_NE(distance, nullptr);
  ASSERT_TRUE(instanceField(*distance).has_value());
  EXPECT_EQ(distance->fields[*instanceField(*distance)].name, "id");
  EXPECT_FALSE(instanceField(*findMessageFields(Heartbeat::kId)).has_value());

  FrameEncoder encoder(7, 1);
  FrameDecoder decoder;
  DistanceSensor d;
  d.time_boot_ms = 12345;
  IrgsEncoderTicks ticks;
  ticks.time_usec = 2'500'000;
  std::vector<Frame> frames;
  for (const EncodedFrame& e :
       {encoder.encode(d), encoder.encode(ticks), encoder.encode(Heartbeat{})})
    for (const Frame& f : decoder.feed(e.view()).frames)
      frames.push_back(f);
  ASSERT_EQ(frames.size(), 3u);
  EXPECT_DOUBLE_EQ(*timeStamp_s(*distance, frames[0]), 12.345);
  EXPECT_DOUBLE_EQ(*timeStamp_s(*findMessageFields(IrgsEncoderTicks::kId), frames[1]), 2.5);
  EXPECT_FALSE(timeStamp_s(*findMessageFields(Heartbeat::kId), frames[2]).has_value());
}

}  // namespace
}  // namespace irgs::comms::mavlink
