// Typed messages: every generated message round-trips through pack/unpack and through a full
// encode/decode, with and without extension fields; a few layouts are checked byte by byte.

#include "comms/mavlink/messages.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <random>
#include <tuple>
#include <vector>

#include "comms/mavlink/frame_decoder.hpp"
#include "comms/mavlink/frame_encoder.hpp"

namespace irgs::comms::mavlink {
namespace {

template <class M>
std::array<std::uint8_t, M::kMaxLength> packed(const M& m) {
  std::array<std::uint8_t, M::kMaxLength> bytes{};
  m.pack(bytes);
  return bytes;
}

template <class M>
void checkRoundTrip(std::mt19937& rng) {
  SCOPED_TRACE(std::string(M::kName));
  std::uniform_int_distribution<int> byte(0, 255);
  FrameEncoder encoder(1, 1);
  FrameDecoder decoder;
  for (int trial = 0; trial < 20; ++trial) {
    std::array<std::uint8_t, M::kMaxLength> wire{};
    for (auto& b : wire) {
      b = static_cast<std::uint8_t>(byte(rng));
    }
    if (trial % 2 == 1) {  // extensions absent: a MAVLink 1 era sender
      std::fill(wire.begin() + M::kMinLength, wire.end(), std::uint8_t{0});
    }
    // Bytes -> message -> bytes is the identity (compared as bytes: NaN patterns included).
    const M message = M::unpack(wire);
    ASSERT_EQ(packed(message), wire);

    const EncodedFrame frame = encoder.encode(message);
    const DecodeResult result = decoder.feed(frame.view());
    ASSERT_EQ(result.frames.size(), 1u);
    const std::optional<M> decoded = result.frames[0].template as<M>();
    ASSERT_TRUE(decoded.has_value());
    EXPECT_EQ(packed(*decoded), wire);
    if (trial % 2 == 1) {
      EXPECT_LE(result.frames[0].payload_length, M::kMinLength);
    }
  }
  EXPECT_EQ(decoder.totals().frames, 20u);
  EXPECT_EQ(decoder.totals().garbage_bytes, 0u);
}

template <class... Ms>
void checkAll(std::tuple<Ms...>*) {
  std::mt19937 rng(1234);
  (checkRoundTrip<Ms>(rng), ...);
}

TEST(MavlinkMessages, EveryGeneratedMessageRoundTrips) {
  checkAll(static_cast<GeneratedMessageTypes*>(nullptr));
  EXPECT_EQ(std::tuple_size_v<GeneratedMessageTypes>, generatedMessages().size());
}

TEST(MavlinkMessages, FrameAsOtherTypeIsEmpty) {
  FrameEncoder encoder(1, 1);
  FrameDecoder decoder;
  const auto result = decoder.feed(encoder.encode(Heartbeat{}).view());
  ASSERT_EQ(result.frames.size(), 1u);
  EXPECT_TRUE(result.frames[0].as<Heartbeat>().has_value());
  EXPECT_FALSE(result.frames[0].as<SysStatus>().has_value());
}

TEST(MavlinkMessages, CommandLongPacksFloatsFirstThenCommandThenBytes) {
  CommandLong m;
  m.param1 = 1.0f;
  m.param7 = -2.5f;
  m.command = static_cast<std::uint16_t>(MavCmd::kIrgsMoveDistance);
  m.target_system = 1;
  m.target_component = 2;
  m.confirmation = 3;
  const auto bytes = packed(m);
  float p1 = 0;
  float p7 = 0;
  std::memcpy(&p1, bytes.data(), 4);  // host is little-endian on every CI target
  std::memcpy(&p7, bytes.data() + 24, 4);
  EXPECT_EQ(p1, 1.0f);
  EXPECT_EQ(p7, -2.5f);
  EXPECT_EQ(bytes[28], 48100 & 0xFF);
  EXPECT_EQ(bytes[29], 48100 >> 8);
  EXPECT_EQ(bytes[30], 1);
  EXPECT_EQ(bytes[31], 2);
  EXPECT_EQ(bytes[32], 3);
  EXPECT_EQ(CommandLong::unpack(bytes), m);
}

TEST(MavlinkMessages, OdometryExtensionsFollowTheBaseFieldsInXmlOrder) {
  Odometry m;
  m.frame_id = 20;      // last base field (uint8, sorted after all floats)
  m.reset_counter = 7;  // extensions: reset_counter, estimator_type, quality
  m.estimator_type = 8;
  m.quality = -1;
  const auto bytes = packed(m);
  EXPECT_EQ(Odometry::kMinLength, 230);
  EXPECT_EQ(bytes[228], 20);
  EXPECT_EQ(bytes[230], 7);
  EXPECT_EQ(bytes[231], 8);
  EXPECT_EQ(bytes[232], 0xFF);
}

TEST(MavlinkMessages, MissingExtensionBytesUnpackAsZero) {
  Odometry m;
  m.x = 1.5f;
  m.frame_id = 20;
  m.reset_counter = 7;
  const auto bytes = packed(m);
  const Odometry cut = Odometry::unpack(std::span(bytes).first(Odometry::kMinLength));
  EXPECT_EQ(cut.x, 1.5f);
  EXPECT_EQ(cut.frame_id, 20);
  EXPECT_EQ(cut.reset_counter, 0);
  // Even an empty payload unpacks (all zero), never reads out of bounds.
  EXPECT_EQ(Odometry::unpack({}).frame_id, 0);
}

TEST(MavlinkMessages, StatustextTextHelpersHandleFullAndShortText) {
  Statustext m;
  setString(m.text, "hello");
  EXPECT_EQ(toStringView(m.text), "hello");
  const std::string full(60, 'x');
  setString(m.text, full);  // cut to 50, no terminator (allowed by the spec at full length)
  EXPECT_EQ(toStringView(m.text), std::string(50, 'x'));
}

TEST(MavlinkMessages, HeartbeatDefaultsToProtocolVersion3) {
  EXPECT_EQ(Heartbeat{}.mavlink_version, 3);
}

TEST(MavlinkMessages, DialectMessagesUseTheirPrivateIdRange) {
  EXPECT_EQ(IrgsStereoSonar::kId, 48000u);
  EXPECT_EQ(IrgsEncoderTicks::kId, 48001u);
  EXPECT_EQ(IrgsContact::kId, 48002u);
  EXPECT_EQ(IrgsBehaviourStatus::kId, 48003u);
  IrgsEncoderTicks ticks;
  ticks.time_usec = 1;
  ticks.left_ticks = -5;
  ticks.right_ticks = 1LL << 40;
  EXPECT_EQ(IrgsEncoderTicks::unpack(packed(ticks)), ticks);
}

// The floor-sensor and caster-encoder messages (issue 5): wire layout (largest elements first)
// and a full encode/decode with values at their type's limits.
TEST(MavlinkMessages, MouseCountsRoundTripWithTheirLayout) {
  EXPECT_EQ(IrgsMouseCounts::kId, 48006u);
  EXPECT_EQ(IrgsMouseCounts::kMinLength, 26);
  IrgsMouseCounts m;
  m.time_usec = 0x0102030405060708ULL;
  m.right_x = -2;
  m.right_y = std::numeric_limits<std::int32_t>::max();
  m.left_x = std::numeric_limits<std::int32_t>::min();
  m.left_y = 31496;  // one metre at 800 cpi
  m.right_status = static_cast<std::uint8_t>(IrgsMouseStatus::kSaturated);
  m.left_status = static_cast<std::uint8_t>(IrgsMouseStatus::kLifted);
  const auto bytes = packed(m);
  EXPECT_EQ(bytes[0], 0x08);  // time_usec, little-endian
  EXPECT_EQ(bytes[7], 0x01);
  EXPECT_EQ(bytes[8], 0xFE);  // right_x = -2
  EXPECT_EQ(bytes[11], 0xFF);
  EXPECT_EQ(bytes[24], 1);  // right_status
  EXPECT_EQ(bytes[25], 2);  // left_status
  FrameEncoder encoder(1, 1);
  FrameDecoder decoder;
  const DecodeResult r = decoder.feed(encoder.encode(m).view());
  ASSERT_EQ(r.frames.size(), 1u);
  EXPECT_EQ(r.frames[0].message_id, 48006u);
  EXPECT_EQ(r.frames[0].as<IrgsMouseCounts>(), m);
}

TEST(MavlinkMessages, CasterEncodersRoundTripWithTheirLayout) {
  EXPECT_EQ(IrgsCasterEncoders::kId, 48007u);
  EXPECT_EQ(IrgsCasterEncoders::kMinLength, 45);
  IrgsCasterEncoders m;
  m.time_usec = 123456789;
  m.residual_sum = 1234.5678901234567;  // double: the cumulative sum keeps its precision
  m.drive = {100, -200, std::numeric_limits<std::int32_t>::max()};
  m.steering = {-8482, 0, 8482};   // -pi, 0, pi at 2700 counts/rad
  m.residual_periods = 3'600'000;  // an hour at 1 ms
  m.flags = static_cast<std::uint8_t>(IrgsCasterFlags::kResidualValid);
  const auto bytes = packed(m);
  double sum = 0.0;
  std::memcpy(&sum, bytes.data() + 8, sizeof sum);  // the two 8-byte fields first
  EXPECT_EQ(sum, m.residual_sum);
  std::int32_t drive0 = 0;
  std::memcpy(&drive0, bytes.data() + 16, sizeof drive0);  // then the int32 arrays in XML order
  EXPECT_EQ(drive0, 100);
  std::int32_t steering2 = 0;
  std::memcpy(&steering2, bytes.data() + 16 + 5 * 4, sizeof steering2);
  EXPECT_EQ(steering2, 8482);
  EXPECT_EQ(bytes[44], 1);  // flags, the only 1-byte field, last
  FrameEncoder encoder(1, 1);
  FrameDecoder decoder;
  const DecodeResult r = decoder.feed(encoder.encode(m).view());
  ASSERT_EQ(r.frames.size(), 1u);
  EXPECT_EQ(r.frames[0].as<IrgsCasterEncoders>(), m);
  // A frame without the residual (flags 0, sum and periods 0) is trimmed, and still decodes.
  IrgsCasterEncoders bare = m;
  bare.residual_sum = 0.0;
  bare.residual_periods = 0;
  bare.flags = 0;
  const DecodeResult b = decoder.feed(encoder.encode(bare).view());
  ASSERT_EQ(b.frames.size(), 1u);
  EXPECT_LT(b.frames[0].payload_length, IrgsCasterEncoders::kMinLength);
  EXPECT_EQ(b.frames[0].as<IrgsCasterEncoders>(), bare);
}

}  // namespace
}  // namespace irgs::comms::mavlink
