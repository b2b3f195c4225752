#include "comms/mavlink/signing.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "comms/mavlink/frame_decoder.hpp"
#include "comms/mavlink/frame_encoder.hpp"
#include "comms/mavlink/messages.hpp"
#include "test_support.hpp"

namespace irgs::comms::mavlink {
namespace {

using test::fromHex;
using Bytes = std::vector<std::uint8_t>;

SigningKey testKey() {
  SigningKey key{};
  for (std::size_t i = 0; i < key.size(); ++i) {
    key[i] = static_cast<std::uint8_t>(i);
  }
  return key;
}

Heartbeat roverHeartbeat() {
  Heartbeat hb;
  hb.custom_mode = 0x01020304;
  hb.type = 10;
  hb.autopilot = 8;
  hb.base_mode = 0x81;
  hb.system_status = 4;
  return hb;
}

// Built by the spec and cross-checked with Python's hashlib: key 00 01 .. 1f, link id 3,
// timestamp 0x0123456789AB, the HEARTBEAT of the encoder test with incompat flags = 0x01:
// signature = sha256(key + frame[0 .. 31))[0 .. 6) = 94 ff 27 05 3d b5.
constexpr std::string_view kSignedHeartbeat =
    "fd090100072a01000000040302010a088104037bfc03ab896745230194ff27053db5";

TEST(MavlinkSigning, EncoderProducesTheKnownVector) {
  std::array<std::uint8_t, kMaxFrameLength> out{};
  std::array<std::uint8_t, Heartbeat::kMaxLength> payload{};
  roverHeartbeat().pack(payload);
  const SignatureFields sig{testKey(), 3, 0x0123456789AB};
  const std::size_t n =
      encodeFrame(out, messageInfoOf<Heartbeat>(), payload, FrameHeaderFields{7, 42, 1, 0}, &sig);
  EXPECT_EQ(Bytes(out.begin(), out.begin() + static_cast<std::ptrdiff_t>(n)),
            fromHex(kSignedHeartbeat));
}

TEST(MavlinkSigning, DecoderVerifiesTheKnownVector) {
  FrameDecoder decoder(DecoderConfig{.signing_key = testKey()});
  const DecodeResult r = decoder.feed(fromHex(kSignedHeartbeat));
  ASSERT_EQ(r.frames.size(), 1u);
  EXPECT_TRUE(r.frames[0].is_signed);
  EXPECT_TRUE(r.frames[0].signature_verified);
  EXPECT_EQ(r.frames[0].link_id, 3);
  EXPECT_EQ(r.frames[0].signature_timestamp, 0x0123456789ABu);
  EXPECT_EQ(r.frames[0].as<Heartbeat>()->custom_mode, 0x01020304u);
}

TEST(MavlinkSigning, WrongKeyIsABadSignature) {
  SigningKey other = testKey();
  other[0] ^= 1;
  FrameDecoder decoder(DecoderConfig{.signing_key = other});
  const Bytes bytes = fromHex(kSignedHeartbeat);
  const DecodeResult r = decoder.feed(bytes);
  EXPECT_TRUE(r.frames.empty());
  EXPECT_EQ(r.counters.bad_signature, 1u);
  EXPECT_EQ(r.counters.garbage_bytes, 0u);  // the checksum was fine: a whole frame, not garbage
}

TEST(MavlinkSigning, TamperedSignatureIsRejected) {
  Bytes bytes = fromHex(kSignedHeartbeat);
  bytes.back() ^= 0x01;
  FrameDecoder decoder(DecoderConfig{.signing_key = testKey()});
  EXPECT_EQ(decoder.feed(bytes).counters.bad_signature, 1u);
}

TEST(MavlinkSigning, WithoutAKeySignedFramesAreDeliveredUnverified) {
  FrameDecoder decoder;
  const DecodeResult r = decoder.feed(fromHex(kSignedHeartbeat));
  ASSERT_EQ(r.frames.size(), 1u);
  EXPECT_TRUE(r.frames[0].is_signed);
  EXPECT_FALSE(r.frames[0].signature_verified);
}

TEST(MavlinkSigning, ReplayedFramesAreRejected) {
  FrameDecoder decoder(DecoderConfig{.signing_key = testKey()});
  const Bytes bytes = fromHex(kSignedHeartbeat);
  EXPECT_EQ(decoder.feed(bytes).frames.size(), 1u);
  const DecodeResult again = decoder.feed(bytes);
  EXPECT_TRUE(again.frames.empty());
  EXPECT_EQ(again.counters.replay_rejected, 1u);
}

TEST(MavlinkSigning, TimestampsMustIncreasePerStream) {
  FrameEncoder robot(1, 1);
  robot.enableSigning(testKey(), 0);
  FrameEncoder other(2, 1);
  other.enableSigning(testKey(), 0);
  const EncodedFrame late = robot.encode(Heartbeat{}, 5'000'000);
  const EncodedFrame early = robot.encode(Heartbeat{}, 1'000);  // clock stepped back
  EXPECT_GT(robot.lastSigningTimestamp(), 5'000'000u);          // encoder stays monotonic

  FrameDecoder decoder(DecoderConfig{.signing_key = testKey()});
  EXPECT_EQ(decoder.feed(late.view()).frames.size(), 1u);
  EXPECT_EQ(decoder.feed(early.view()).frames.size(), 1u);

  // A frame of the same stream with an older timestamp (an attacker's recording) is dropped,
  // while another sender's stream is independent.
  FrameEncoder recorder(1, 1);
  recorder.enableSigning(testKey(), 0);
  const DecodeResult replay = decoder.feed(recorder.encode(Heartbeat{}, 4'000'000).view());
  EXPECT_EQ(replay.counters.replay_rejected, 1u);
  EXPECT_EQ(decoder.feed(other.encode(Heartbeat{}, 4'999'000).view()).frames.size(), 1u);
}

TEST(MavlinkSigning, NewStreamMoreThanAMinuteOldIsRejected) {
  FrameEncoder a(1, 1);
  a.enableSigning(testKey(), 0);
  FrameEncoder b(2, 1);
  b.enableSigning(testKey(), 0);
  const std::uint64_t now = 100 * kSigningTicksPerSecond;
  FrameDecoder decoder(DecoderConfig{.signing_key = testKey()});
  EXPECT_EQ(decoder.feed(a.encode(Heartbeat{}, now).view()).frames.size(), 1u);
  const DecodeResult old =
      decoder.feed(b.encode(Heartbeat{}, now - 61 * kSigningTicksPerSecond).view());
  EXPECT_EQ(old.counters.replay_rejected, 1u);
}

// A receiver that has just started knows the time: a recording of signed frames made more than a
// minute ago is a replay even though it opens a stream the receiver has never seen.
TEST(MavlinkSigning, ASigningClockRefusesANewStreamMoreThanAMinuteOld) {
  FrameEncoder recorded(1, 1);
  recorded.enableSigning(testKey(), 0);
  const std::uint64_t now = 1000 * kSigningTicksPerSecond;
  const Bytes old_frame = [&] {
    const EncodedFrame f = recorded.encode(Heartbeat{}, now - 120 * kSigningTicksPerSecond);
    return Bytes(f.view().begin(), f.view().end());
  }();
  FrameDecoder unaware(DecoderConfig{.signing_key = testKey()});
  EXPECT_EQ(unaware.feed(old_frame).frames.size(), 1u);  // without a clock: accepted
  FrameDecoder aware(DecoderConfig{.signing_key = testKey()});
  aware.setSigningClock(now);
  const DecodeResult r = aware.feed(old_frame);
  EXPECT_TRUE(r.frames.empty());
  EXPECT_EQ(r.counters.replay_rejected, 1u);
  // A live sender whose clock is a few seconds behind is still accepted; the clock never goes
  // back.
  FrameEncoder live(2, 1);
  live.enableSigning(testKey(), 0);
  aware.setSigningClock(now - 500 * kSigningTicksPerSecond);
  EXPECT_EQ(
      aware.feed(live.encode(Heartbeat{}, now - 5 * kSigningTicksPerSecond).view()).frames.size(),
      1u);
}

TEST(MavlinkSigning, UnsignedFramesAreRejectedOnlyWhenRequired) {
  FrameEncoder plain(1, 1);
  const EncodedFrame f = plain.encode(Heartbeat{});
  FrameDecoder lenient(DecoderConfig{.signing_key = testKey(), .require_signed = false});
  EXPECT_EQ(lenient.feed(f.view()).frames.size(), 1u);
  FrameDecoder strict(DecoderConfig{.signing_key = testKey(), .require_signed = true});
  const DecodeResult r = strict.feed(f.view());
  EXPECT_TRUE(r.frames.empty());
  EXPECT_EQ(r.counters.unsigned_rejected, 1u);
}

TEST(MavlinkSigning, SignedStreamRoundTripsThroughSplitFeeds) {
  FrameEncoder encoder(9, 9);
  encoder.enableSigning(testKey(), 7);
  Bytes stream;
  for (int i = 0; i < 10; ++i) {
    const EncodedFrame f = encoder.encode(roverHeartbeat(), static_cast<std::uint64_t>(i) * 100);
    stream.insert(stream.end(), f.view().begin(), f.view().end());
  }
  FrameDecoder decoder(DecoderConfig{.signing_key = testKey(), .require_signed = true});
  std::vector<Frame> frames;
  for (std::size_t i = 0; i < stream.size(); i += 7) {
    decoder.feed(std::span(stream).subspan(i, std::min<std::size_t>(7, stream.size() - i)), frames);
  }
  ASSERT_EQ(frames.size(), 10u);
  for (const Frame& f : frames) {
    EXPECT_TRUE(f.signature_verified);
    EXPECT_EQ(f.link_id, 7);
  }
}

TEST(MavlinkSigning, TimestampCountsTenMicrosecondsSince2015) {
  using namespace std::chrono;
  const system_clock::time_point epoch{seconds{kSigningEpochUnixSeconds}};
  EXPECT_EQ(signingTimestampAt(epoch), 0u);
  EXPECT_EQ(signingTimestampAt(epoch - seconds{1}), 0u);
  EXPECT_EQ(signingTimestampAt(epoch + seconds{1}), 100000u);
  EXPECT_EQ(signingTimestampAt(epoch + microseconds{25}), 2u);
  // 2015-01-01 is 1420070400 s after the Unix epoch.
  EXPECT_EQ(kSigningEpochUnixSeconds, 45LL * 365 * 86400 + 11 * 86400);
}

TEST(MavlinkSigning, KeyFromPassphraseIsItsSha256) {
  const SigningKey key = signingKeyFromPassphrase("irgs");
  EXPECT_EQ(Bytes(key.begin(), key.end()),
            fromHex("0766b5b6ee95bc4f5ea7ab373404d499b886d078d06cde5181d64032c04a0b65"));
}

}  // namespace
}  // namespace irgs::comms::mavlink
