#include "comms/arcos/arcos_packet.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <vector>

#include "comms/arcos/arcos_commands.hpp"

namespace irgs::comms::arcos {
namespace {

using Bytes = std::vector<std::uint8_t>;
using ::testing::ElementsAre;

std::vector<Packet> decodeAll(PacketDecoder& decoder, const Bytes& bytes) {
  std::vector<Packet> out;
  decoder.feed(bytes, out);
  return out;
}

Bytes payloadOf(const Packet& p) {
  return {p.payload().begin(), p.payload().end()};
}

TEST(ArcosChecksum, AddsBigEndianWordsAndXorsAnOddLastByte) {
  EXPECT_EQ(checksum(Bytes{0x0b, 0x3b, 0xc8, 0x00}), 0xd33b);  // even: 0x0b3b + 0xc800
  EXPECT_EQ(checksum(Bytes{0x01}), 0x0001);                    // odd, only the XOR
  EXPECT_EQ(checksum(Bytes{0x12, 0x34, 0x56}), 0x1234 ^ 0x56);
  // The running sum wraps at 16 bits before the odd byte is XORed in.
  EXPECT_EQ(checksum(Bytes{0xff, 0xff, 0x00, 0x02, 0x80}), ((0xffff + 0x0002) & 0xffff) ^ 0x80);
}

TEST(ArcosCommandPackets, AreByteExactForTheManualsExamples) {
  EXPECT_THAT(commandPacket(kOpen), ElementsAre(0xfa, 0xfb, 0x03, 0x01, 0x00, 0x01));
  EXPECT_THAT(commandPacket(Command::kVel, 200),
              ElementsAre(0xfa, 0xfb, 0x06, 0x0b, 0x3b, 0xc8, 0x00, 0xd3, 0x3b));
  EXPECT_THAT(commandPacket(kPulse), ElementsAre(0xfa, 0xfb, 0x03, 0x00, 0x00, 0x00));
  EXPECT_THAT(commandPacket(Command::kSync2), ElementsAre(0xfa, 0xfb, 0x03, 0x02, 0x00, 0x02));
}

TEST(ArcosCommandPackets, EncodeNegativeArgumentsAsMagnitudeWithTheNegativeType) {
  // RVEL -10 deg/s: 15 1b 0a 00, checksum 0x151b + 0x0a00 = 0x1f1b.
  EXPECT_THAT(commandPacket(Command::kRVel, -10),
              ElementsAre(0xfa, 0xfb, 0x06, 0x15, 0x1b, 0x0a, 0x00, 0x1f, 0x1b));
  const auto parsed = parseCommand(commandPayload(Command::kRVel, -10));
  ASSERT_TRUE(parsed.command);
  EXPECT_EQ(parsed.command->int_argument, -10);
  EXPECT_THROW(commandPayload(Command::kVel, 40000), std::invalid_argument);
}

TEST(ArcosCommandPackets, CarryStringArgumentsWithALengthByte) {
  const Bytes payload = commandPayload(15, std::string_view("hi"));
  EXPECT_THAT(payload, ElementsAre(15, 0x2b, 2, 'h', 'i'));
  const auto parsed = parseCommand(payload);
  ASSERT_TRUE(parsed.command);
  EXPECT_EQ(parsed.command->string_argument, "hi");
  EXPECT_FALSE(parseCommand(Bytes{15, 0x2b, 5, 'h'}).command);  // truncated string
  EXPECT_FALSE(parseCommand(Bytes{11, 0x3b, 0xc8}).command);    // truncated int
  EXPECT_THAT(parseCommand(Bytes{11, 0x99, 0, 0}).error, ::testing::HasSubstr("0x99"));
}

TEST(ArcosVel2, PacksLeftInTheHighByteAndRightInTheLowByteAsSignedBytes) {
  const int argument = vel2Argument(-5, 10);
  EXPECT_EQ(argument, static_cast<std::int16_t>(0xfb0a));
  // As ARIA sends it: a negative int argument whose magnitude is -(int16)0xfb0a = 0x04f6.
  EXPECT_THAT(commandPayload(32, argument), ElementsAre(32, 0x1b, 0xf6, 0x04));
  EXPECT_EQ(splitVel2Argument(-1270).left, -5);
  const WheelUnits wheels = splitVel2Argument(argument);
  EXPECT_EQ(wheels.left, -5);
  EXPECT_EQ(wheels.right, 10);
  EXPECT_EQ(splitVel2Argument(vel2Argument(500, -500)).left, 127);  // clamped
  EXPECT_EQ(splitVel2Argument(vel2Argument(500, -500)).right, -127);
}

TEST(ArcosPacketDecoder, DeliversPacketsSplitAcrossFeedsOneByteAtATime) {
  PacketDecoder decoder;
  const Bytes packet = commandPacket(Command::kVel, 200);
  std::vector<Packet> out;
  for (std::uint8_t b : packet)
    decoder.feed(Bytes{b}, out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_THAT(payloadOf(out[0]), ElementsAre(0x0b, 0x3b, 0xc8, 0x00));
  EXPECT_EQ(decoder.totals().garbage_bytes, 0u);
}

TEST(ArcosPacketDecoder, SkipsGarbageAndBadChecksumsAndFindsThePacketInside) {
  PacketDecoder decoder;
  // Noise, then a false header whose count (4) swallows the start of the next packet.
  Bytes stream{0x00, 0xfa, 0x17, 0xfa, 0xfb, 0x04};
  Bytes bad = commandPacket(Command::kVel, 200);
  bad.back() ^= 0x01;  // checksum broken
  stream.insert(stream.end(), bad.begin(), bad.end());
  const Bytes good = commandPacket(kOpen);
  stream.insert(stream.end(), good.begin(), good.end());
  const auto out = decodeAll(decoder, stream);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_THAT(payloadOf(out[0]), ElementsAre(0x01));
  EXPECT_GE(decoder.totals().bad_checksum, 1u);
  // Every byte before the good packet is garbage, none of the good one.
  EXPECT_EQ(decoder.totals().garbage_bytes, stream.size() - good.size());
}

TEST(ArcosPacketDecoder, RejectsCountsTooSmallForAPayload) {
  PacketDecoder decoder;
  Bytes stream{0xfa, 0xfb, 0x02, 0x00, 0x00};
  const Bytes good = commandPacket(kOpen);
  stream.insert(stream.end(), good.begin(), good.end());
  const auto out = decodeAll(decoder, stream);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(decoder.totals().bad_count, 1u);
}

TEST(ArcosPacketDecoder, NeverDeliversACorruptedPacketFromRandomNoise) {
  std::mt19937 rng(7);
  PacketDecoder decoder;
  std::vector<Bytes> sent;
  Bytes stream;
  for (int i = 0; i < 2000; ++i) {
    const Bytes packet = commandPacket(Command::kVel, static_cast<int>(rng() % 2000) - 1000);
    sent.emplace_back(packet.begin() + 3, packet.end() - 2);
    stream.insert(stream.end(), packet.begin(), packet.end());
    for (unsigned k = rng() % 4; k > 0; --k)
      stream.push_back(static_cast<std::uint8_t>(rng()));
  }
  std::vector<Packet> out;
  std::size_t offset = 0;
  while (offset < stream.size()) {
    const std::size_t n = std::min<std::size_t>(1 + rng() % 97, stream.size() - offset);
    decoder.feed(std::span(stream).subspan(offset, n), out);
    offset += n;
  }
  // Random noise can forge a valid-checksum packet only rarely; every genuine packet is found.
  std::size_t matched = 0;
  std::size_t next = 0;
  for (const Packet& p : out) {
    const Bytes got = payloadOf(p);
    for (std::size_t j = next; j < sent.size(); ++j) {
      if (sent[j] == got) {
        ++matched;
        next = j + 1;
        break;
      }
    }
  }
  EXPECT_EQ(matched, sent.size());
  EXPECT_LE(out.size() - matched, 5u);
}

TEST(ArcosFramePacket, RejectsEmptyAndOversizedPayloads) {
  EXPECT_THROW(framePacket(Bytes{}), std::invalid_argument);
  EXPECT_THROW(framePacket(Bytes(kMaxPayload + 1, 0)), std::invalid_argument);
  EXPECT_EQ(framePacket(Bytes(kMaxPayload, 1)).size(), kMaxPayload + kOverhead);
}

}  // namespace
}  // namespace irgs::comms::arcos
