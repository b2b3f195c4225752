#include "comms/mavlink/frame_decoder.hpp"

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "comms/mavlink/frame_encoder.hpp"
#include "comms/mavlink/messages.hpp"
#include "test_support.hpp"

namespace irgs::comms::mavlink {
namespace {

using test::fromHex;
using Bytes = std::vector<std::uint8_t>;

void append(Bytes& out, const EncodedFrame& f) {
  out.insert(out.end(), f.view().begin(), f.view().end());
}

// A mixed stream: heartbeat, sonar, odometry, status text, dialect message.
Bytes mixedStream(FrameEncoder& encoder, int rounds) {
  Bytes bytes;
  for (int i = 0; i < rounds; ++i) {
    Heartbeat hb;
    hb.custom_mode = static_cast<std::uint32_t>(i);
    append(bytes, encoder.encode(hb));
    DistanceSensor ds;
    ds.current_distance = static_cast<std::uint16_t>(100 + i);
    ds.id = static_cast<std::uint8_t>(i % 8);
    append(bytes, encoder.encode(ds));
    Odometry od;
    od.x = static_cast<float>(i) * 0.1f;
    od.frame_id = 1;
    append(bytes, encoder.encode(od));
    Statustext st;
    setString(st.text, "tick " + std::to_string(i));
    append(bytes, encoder.encode(st));
    IrgsEncoderTicks ticks;
    ticks.left_ticks = i;
    ticks.right_ticks = -i;
    append(bytes, encoder.encode(ticks));
  }
  return bytes;
}

TEST(MavlinkFrameDecoder, DecodesAHandBuiltHeartbeat) {
  FrameDecoder decoder;
  const Bytes bytes = fromHex("fd090000072a01000000040302010a088104039c04");
  const DecodeResult r = decoder.feed(bytes);
  ASSERT_EQ(r.frames.size(), 1u);
  const Frame& f = r.frames[0];
  EXPECT_EQ(f.version, ProtocolVersion::kV2);
  EXPECT_EQ(f.sequence, 7);
  EXPECT_EQ(f.system_id, 42);
  EXPECT_EQ(f.component_id, 1);
  EXPECT_FALSE(f.is_signed);
  const auto hb = f.as<Heartbeat>();
  ASSERT_TRUE(hb);
  EXPECT_EQ(hb->custom_mode, 0x01020304u);
  EXPECT_EQ(hb->type, static_cast<std::uint8_t>(MavType::kGroundRover));
  EXPECT_EQ(hb->base_mode, 0x81);
  EXPECT_EQ(hb->mavlink_version, 3);
  EXPECT_EQ(r.counters.frames, 1u);
  EXPECT_EQ(decoder.bufferedBytes(), 0u);
}

TEST(MavlinkFrameDecoder, ReExtendsATrimmedPayloadWithZeros) {
  const Bytes bytes = fromHex("fd060000000101fd00000668656c6c6f4795");  // STATUSTEXT, len 6
  FrameDecoder decoder;
  const DecodeResult r = decoder.feed(bytes);
  ASSERT_EQ(r.frames.size(), 1u);
  EXPECT_EQ(r.frames[0].payload_length, 6);
  const auto st = r.frames[0].as<Statustext>();
  ASSERT_TRUE(st);
  EXPECT_EQ(st->severity, 6);
  EXPECT_EQ(toStringView(st->text), "hello");
  EXPECT_EQ(st->id, 0);  // extension fields absent on the wire
  EXPECT_EQ(st->chunk_seq, 0);
  for (std::size_t i = 6; i < Statustext::kMaxLength; ++i) {
    EXPECT_EQ(r.frames[0].payload[i], 0);
  }
}

TEST(MavlinkFrameDecoder, AcceptsMavlink1Frames) {
  FrameDecoder decoder;
  const DecodeResult r = decoder.feed(fromHex("fe09072a0100040302010a088104032857"));
  ASSERT_EQ(r.frames.size(), 1u);
  EXPECT_EQ(r.frames[0].version, ProtocolVersion::kV1);
  EXPECT_EQ(r.frames[0].sequence, 7);
  EXPECT_EQ(r.frames[0].system_id, 42);
  EXPECT_EQ(r.frames[0].as<Heartbeat>()->custom_mode, 0x01020304u);
}

TEST(MavlinkFrameDecoder, IgnoresMavlink1WhenConfigured) {
  FrameDecoder decoder(DecoderConfig{.accept_v1 = false});
  const Bytes bytes = fromHex("fe09072a0100040302010a088104032857");
  const DecodeResult r = decoder.feed(bytes);
  EXPECT_TRUE(r.frames.empty());
  EXPECT_EQ(r.counters.garbage_bytes, bytes.size());
}

TEST(MavlinkFrameDecoder, GivesTheSameFramesForEverySplitOfTheStream) {
  FrameEncoder encoder(3, 4);
  const Bytes stream = mixedStream(encoder, 3);
  FrameDecoder whole;
  const std::size_t expected = whole.feed(stream).frames.size();
  ASSERT_EQ(expected, 15u);
  for (std::size_t split = 0; split <= stream.size(); ++split) {
    FrameDecoder decoder;
    std::vector<Frame> frames;
    decoder.feed(std::span(stream).first(split), frames);
    decoder.feed(std::span(stream).subspan(split), frames);
    ASSERT_EQ(frames.size(), expected) << "split at " << split;
    EXPECT_EQ(decoder.totals().garbage_bytes, 0u);
    EXPECT_EQ(decoder.totals().sequence_gaps, 0u);
  }
  // And one byte at a time.
  FrameDecoder decoder;
  std::vector<Frame> frames;
  for (const std::uint8_t b : stream) {
    decoder.feed(std::span(&b, 1), frames);
  }
  ASSERT_EQ(frames.size(), expected);
  EXPECT_EQ(frames[2].as<Odometry>()->x, 0.0f);
  EXPECT_EQ(frames[7].as<Odometry>()->x, 0.1f);
}

TEST(MavlinkFrameDecoder, ResynchronisesAfterGarbageAndCountsIt) {
  FrameEncoder encoder(1, 1);
  // Garbage without any STX byte, so none of it can start a frame.
  const Bytes garbage = {0x00, 0x11, 0x22, 0xFF, 0x13, 0x37};
  Bytes stream = garbage;
  append(stream, encoder.encode(Heartbeat{}));
  stream.insert(stream.end(), garbage.begin(), garbage.end());
  append(stream, encoder.encode(Heartbeat{}));
  FrameDecoder decoder;
  const DecodeResult r = decoder.feed(stream);
  EXPECT_EQ(r.frames.size(), 2u);
  EXPECT_EQ(r.counters.garbage_bytes, 2 * garbage.size());
  EXPECT_EQ(r.counters.bad_crc, 0u);
}

TEST(MavlinkFrameDecoder, FindsARealFrameThatStartsInsideAFalseStart) {
  FrameEncoder encoder(1, 1);
  // A complete false header (STX, len 9, HEARTBEAT id) claims the next 11 bytes, which are the
  // start of a real frame; the decoder must back off after the CRC fails and find it.
  Bytes stream = {kStxV2, 9, 0, 0, 0, 1, 1, 0, 0, 0};
  append(stream, encoder.encode(Heartbeat{}));
  append(stream, encoder.encode(Heartbeat{}));
  FrameDecoder decoder;
  const DecodeResult r = decoder.feed(stream);
  EXPECT_EQ(r.frames.size(), 2u);
  EXPECT_EQ(r.counters.bad_crc, 1u);
  EXPECT_EQ(r.counters.garbage_bytes, 10u);
}

TEST(MavlinkFrameDecoder, CountsBadCrcAndKeepsTheNextFrame) {
  FrameEncoder encoder(1, 1);
  EncodedFrame bad = encoder.encode(Heartbeat{});
  bad.bytes[12] ^= 0x40;  // payload bit flip
  Bytes stream;
  append(stream, bad);
  append(stream, encoder.encode(Heartbeat{}));
  FrameDecoder decoder;
  const DecodeResult r = decoder.feed(stream);
  EXPECT_EQ(r.frames.size(), 1u);
  EXPECT_EQ(r.frames[0].sequence, 1);
  EXPECT_EQ(r.counters.bad_crc, 1u);
  EXPECT_EQ(r.counters.garbage_bytes, bad.size);
}

TEST(MavlinkFrameDecoder, CountsUnknownIdsBadLengthsAndUnsupportedFlags) {
  FrameEncoder encoder(1, 1);
  std::array<std::uint8_t, kMaxFrameLength> out{};
  const MessageInfo unknown{4242, 0, 1, 1, "UNKNOWN"};
  const std::array<std::uint8_t, 1> one{1};
  Bytes stream;
  const std::size_t n = encodeFrame(out, unknown, one, {});
  stream.insert(stream.end(), out.begin(), out.begin() + static_cast<std::ptrdiff_t>(n));
  EncodedFrame too_long = encoder.encode(Heartbeat{});
  too_long.bytes[1] = 10;  // HEARTBEAT is at most 9 bytes
  append(stream, too_long);
  EncodedFrame flagged = encoder.encode(Heartbeat{});
  flagged.bytes[2] = 0x02;  // an incompat flag we do not implement
  append(stream, flagged);
  append(stream, encoder.encode(Heartbeat{}));

  FrameDecoder decoder;
  const DecodeResult r = decoder.feed(stream);
  ASSERT_EQ(r.frames.size(), 1u);
  EXPECT_EQ(r.counters.unknown_id, 1u);
  EXPECT_EQ(r.counters.bad_length, 1u);
  EXPECT_EQ(r.counters.unsupported_flags, 1u);
  EXPECT_EQ(r.counters.bad_crc, 0u);
  EXPECT_EQ(r.counters.garbage_bytes, stream.size() - r.frames[0].payload_length - 12);
}

TEST(MavlinkFrameDecoder, RejectsMavlink1FramesShorterThanTheBaseFields) {
  std::array<std::uint8_t, kMaxFrameLength> out{};
  MessageInfo info = messageInfoOf<Heartbeat>();
  info.min_length = 5;  // craft a v1 frame of 5 bytes with the right CRC
  const std::size_t n = encodeFrameV1(out, info, {}, {});
  FrameDecoder decoder;
  const DecodeResult r = decoder.feed(std::span(out).first(n));
  EXPECT_TRUE(r.frames.empty());
  EXPECT_EQ(r.counters.bad_length, 1u);
}

TEST(MavlinkFrameDecoder, CountsSequenceGapsPerSender) {
  FrameEncoder a(1, 1);
  FrameEncoder b(2, 1);
  Bytes stream;
  append(stream, a.encode(Heartbeat{}));  // a: 0
  append(stream, b.encode(Heartbeat{}));  // b: 0
  (void)a.encode(Heartbeat{});            // a: 1 lost
  (void)a.encode(Heartbeat{});            // a: 2 lost
  append(stream, a.encode(Heartbeat{}));  // a: 3
  append(stream, b.encode(Heartbeat{}));  // b: 1
  FrameDecoder decoder;
  const DecodeResult r = decoder.feed(stream);
  EXPECT_EQ(r.frames.size(), 4u);
  EXPECT_EQ(r.counters.sequence_gaps, 2u);
}

TEST(MavlinkFrameDecoder, SequenceWrapIsNotAGapAndDuplicatesAreNotCounted) {
  FrameEncoder encoder(1, 1);
  Bytes stream;
  for (int i = 0; i < 300; ++i) {
    append(stream, encoder.encode(Heartbeat{}));
  }
  const EncodedFrame last = encoder.encode(Heartbeat{});
  append(stream, last);
  append(stream, last);  // the same frame twice (e.g. via two routes)
  FrameDecoder decoder;
  const DecodeResult r = decoder.feed(stream);
  EXPECT_EQ(r.frames.size(), 302u);
  EXPECT_EQ(r.counters.sequence_gaps, 0u);
}

TEST(MavlinkFrameDecoder, ReusesItsOutputAndAccumulatesTotals) {
  FrameEncoder encoder(1, 1);
  FrameDecoder decoder;
  for (int i = 0; i < 3; ++i) {
    const DecodeResult r = decoder.feed(encoder.encode(Heartbeat{}).view());
    EXPECT_EQ(r.frames.size(), 1u);
    EXPECT_EQ(r.counters.frames, 1u);
  }
  EXPECT_EQ(decoder.totals().frames, 3u);
}

TEST(MavlinkFrameDecoder, ResetDropsAPartialFrame) {
  FrameEncoder encoder(1, 1);
  const EncodedFrame f = encoder.encode(Heartbeat{});
  FrameDecoder decoder;
  (void)decoder.feed(f.view().first(5));
  EXPECT_EQ(decoder.bufferedBytes(), 5u);
  decoder.reset();
  EXPECT_EQ(decoder.bufferedBytes(), 0u);
  EXPECT_EQ(decoder.feed(f.view()).frames.size(), 1u);
}

TEST(MavlinkFrameDecoder, RefusesAnUnsortedMessageTable) {
  const std::array<MessageInfo, 2> table{MessageInfo{5, 0, 1, 1, "B"},
                                         MessageInfo{1, 0, 1, 1, "A"}};
  EXPECT_THROW(FrameDecoder(DecoderConfig{.messages = table}), std::invalid_argument);
}

TEST(MavlinkFrameDecoder, DecodesOnlyTheMessagesOfItsTable) {
  const std::array<MessageInfo, 1> only_heartbeat{messageInfoOf<Heartbeat>()};
  FrameEncoder encoder(1, 1);
  Bytes stream;
  append(stream, encoder.encode(SysStatus{}));
  append(stream, encoder.encode(Heartbeat{}));
  FrameDecoder decoder(DecoderConfig{.messages = only_heartbeat});
  const DecodeResult r = decoder.feed(stream);
  ASSERT_EQ(r.frames.size(), 1u);
  EXPECT_EQ(r.frames[0].message_id, Heartbeat::kId);
  EXPECT_EQ(r.counters.unknown_id, 1u);
}

}  // namespace
}  // namespace irgs::comms::mavlink
