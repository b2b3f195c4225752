#include "comms/mavlink/frame_encoder.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "comms/mavlink/messages.hpp"
#include "test_support.hpp"

namespace irgs::comms::mavlink {
namespace {

using test::fromHex;

std::vector<std::uint8_t> bytesOf(const EncodedFrame& f) {
  return {f.view().begin(), f.view().end()};
}

Heartbeat roverHeartbeat() {
  Heartbeat hb;
  hb.custom_mode = 0x01020304;
  hb.type = static_cast<std::uint8_t>(MavType::kGroundRover);
  hb.autopilot = static_cast<std::uint8_t>(MavAutopilot::kInvalid);
  hb.base_mode = 0x81;
  hb.system_status = static_cast<std::uint8_t>(MavState::kActive);
  return hb;
}

// Built by hand from the spec: FD len=9 incompat=0 compat=0 seq=7 sys=42 comp=1 id=0,0,0,
// payload custom_mode LE, type, autopilot, base_mode, system_status, mavlink_version, then the
// X.25 CRC over bytes 1..18 plus CRC_EXTRA 50, little-endian (computed independently in Python).
TEST(MavlinkFrameEncoder, HeartbeatIsByteExact) {
  FrameEncoder encoder(42, 1);
  for (int i = 0; i < 7; ++i) {
    (void)encoder.encode(roverHeartbeat());
  }
  EXPECT_EQ(bytesOf(encoder.encode(roverHeartbeat())),
            fromHex("fd090000072a01000000040302010a088104039c04"));
}

TEST(MavlinkFrameEncoder, TrimsTrailingZerosOfThePayload) {
  Statustext st;
  st.severity = static_cast<std::uint8_t>(MavSeverity::kInfo);
  setString(st.text, "hello");
  std::array<std::uint8_t, kMaxFrameLength> out{};
  std::array<std::uint8_t, Statustext::kMaxLength> payload{};
  st.pack(payload);
  const std::size_t n =
      encodeFrame(out, messageInfoOf<Statustext>(), payload, FrameHeaderFields{0, 1, 1, 0});
  EXPECT_EQ(std::vector<std::uint8_t>(out.begin(), out.begin() + static_cast<std::ptrdiff_t>(n)),
            fromHex("fd060000000101fd00000668656c6c6f4795"));
}

TEST(MavlinkFrameEncoder, KeepsOneByteOfAnAllZeroPayload) {
  FrameEncoder encoder(1, 1);
  const EncodedFrame f = encoder.encode(ParamRequestList{});
  EXPECT_EQ(f.bytes[1], 1);  // len
  EXPECT_EQ(f.size, kHeaderLengthV2 + 1 + kChecksumLength);
}

TEST(MavlinkFrameEncoder, NumbersFramesAndWrapsAt256) {
  FrameEncoder encoder(1, 1);
  for (int i = 0; i < 256; ++i) {
    EXPECT_EQ(encoder.encode(Heartbeat{}).bytes[4], static_cast<std::uint8_t>(i));
  }
  EXPECT_EQ(encoder.encode(Heartbeat{}).bytes[4], 0);
}

TEST(MavlinkFrameEncoder, PutsTheThreeByteMessageIdLittleEndian) {
  FrameEncoder encoder(1, 1);
  const EncodedFrame f = encoder.encode(IrgsContact{});
  EXPECT_EQ(f.bytes[7], 48002 & 0xFF);
  EXPECT_EQ(f.bytes[8], (48002 >> 8) & 0xFF);
  EXPECT_EQ(f.bytes[9], 0);
}

TEST(MavlinkFrameEncoder, WritesMavlink1WithoutExtensions) {
  std::array<std::uint8_t, kMaxFrameLength> out{};
  std::array<std::uint8_t, Heartbeat::kMaxLength> payload{};
  roverHeartbeat().pack(payload);
  const std::size_t n =
      encodeFrameV1(out, messageInfoOf<Heartbeat>(), payload, FrameHeaderFields{7, 42, 1, 0});
  EXPECT_EQ(std::vector<std::uint8_t>(out.begin(), out.begin() + static_cast<std::ptrdiff_t>(n)),
            fromHex("fe09072a0100040302010a088104032857"));
}

TEST(MavlinkFrameEncoder, RejectsMisuse) {
  std::array<std::uint8_t, kMaxFrameLength> out{};
  const std::array<std::uint8_t, 10> too_long{};
  EXPECT_THROW(encodeFrame(out, messageInfoOf<Heartbeat>(), too_long, {}), std::invalid_argument);
  EXPECT_THROW(encodeFrameV1(out, messageInfoOf<IrgsContact>(), {}, {}), std::invalid_argument);
}

}  // namespace
}  // namespace irgs::comms::mavlink
