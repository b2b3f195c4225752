// Seeded fuzz-style tests: random mutations of a valid stream and pure noise. The decoder must
// never crash, never deliver a frame that did not arrive with a matching checksum, and account
// for every byte it was fed.

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "comms/mavlink/crc.hpp"
#include "comms/mavlink/frame_decoder.hpp"
#include "comms/mavlink/frame_encoder.hpp"
#include "comms/mavlink/messages.hpp"

namespace irgs::comms::mavlink {
namespace {

using Bytes = std::vector<std::uint8_t>;

Bytes telemetryStream(int ticks) {
  FrameEncoder encoder(1, 1);
  Bytes bytes;
  auto add = [&](const EncodedFrame& f) {
    bytes.insert(bytes.end(), f.view().begin(), f.view().end());
  };
  for (int t = 0; t < ticks; ++t) {
    add(encoder.encode(Heartbeat{}));
    for (std::uint8_t s = 0; s < 8; ++s) {
      DistanceSensor ds;
      ds.id = s;
      ds.current_distance = static_cast<std::uint16_t>(50 + 10 * s + t);
      ds.max_distance = 400;
      add(encoder.encode(ds));
    }
    Odometry od;
    od.time_usec = static_cast<std::uint64_t>(t) * 50000;
    od.x = static_cast<float>(t) * 0.01f;
    od.q = {1, 0, 0, 0};
    od.frame_id = 20;
    add(encoder.encode(od));
    RawImu imu;
    imu.time_usec = od.time_usec;
    imu.zacc = 1000;
    add(encoder.encode(imu));
  }
  return bytes;
}

// The frame as it must have been on the wire (unsigned): header, payload as received, and a
// freshly computed checksum.
Bytes wireImage(const Frame& f) {
  const MessageInfo info = *findMessageInfo(f.message_id);
  const auto id = [&](int shift) { return static_cast<std::uint8_t>(f.message_id >> shift); };
  Bytes b;
  if (f.version == ProtocolVersion::kV2) {
    b = {kStxV2,
         f.payload_length,
         f.incompat_flags,
         f.compat_flags,
         f.sequence,
         f.system_id,
         f.component_id,
         id(0),
         id(8),
         id(16)};
  } else {
    b = {kStxV1, f.payload_length, f.sequence, f.system_id, f.component_id, id(0)};
  }
  b.insert(b.end(), f.payload.begin(), f.payload.begin() + f.payload_length);
  std::uint16_t crc = crcAccumulate(std::span(b).subspan(1));
  crc = crcAccumulate(info.crc_extra, crc);
  b.push_back(static_cast<std::uint8_t>(crc & 0xFF));
  b.push_back(static_cast<std::uint8_t>(crc >> 8));
  return b;
}

std::size_t frameSize(const Frame& f) {
  const std::size_t header = f.version == ProtocolVersion::kV2 ? kHeaderLengthV2 : kHeaderLengthV1;
  return header + f.payload_length + kChecksumLength + (f.is_signed ? kSignatureLength : 0);
}

// Feeds `bytes` in random chunks; checks that every byte is either garbage, part of a delivered
// frame, or still buffered.
std::vector<Frame> decodeInChunks(const Bytes& bytes, std::mt19937& rng, DecodeCounters& totals) {
  FrameDecoder decoder;
  std::vector<Frame> frames;
  std::uniform_int_distribution<std::size_t> chunk(1, 700);
  for (std::size_t i = 0; i < bytes.size();) {
    const std::size_t n = std::min(chunk(rng), bytes.size() - i);
    decoder.feed(std::span(bytes).subspan(i, n), frames);
    i += n;
  }
  totals = decoder.totals();
  std::size_t in_frames = 0;
  for (const Frame& f : frames) {
    in_frames += frameSize(f);
  }
  EXPECT_EQ(totals.garbage_bytes + in_frames + decoder.bufferedBytes(), bytes.size());
  EXPECT_EQ(totals.frames, frames.size());
  return frames;
}

TEST(MavlinkDecoderFuzz, MutatedStreamsNeverDeliverAFrameThatFailedItsChecksum) {
  const Bytes clean = telemetryStream(100);
  std::mt19937 rng(20261122);
  for (int round = 0; round < 20; ++round) {
    Bytes bytes = clean;
    std::uniform_int_distribution<std::size_t> where(0, bytes.size() - 1);
    std::uniform_int_distribution<int> kind(0, 2);
    std::uniform_int_distribution<int> value(0, 255);
    const int mutations = 1 + round * 10;
    for (int m = 0; m < mutations; ++m) {
      const std::size_t at = where(rng) % bytes.size();
      switch (kind(rng)) {
        case 0:
          bytes[at] ^= static_cast<std::uint8_t>(1u << (value(rng) % 8));
          break;
        case 1:
          bytes.erase(bytes.begin() + static_cast<std::ptrdiff_t>(at));
          break;
        default:
          bytes.insert(bytes.begin() + static_cast<std::ptrdiff_t>(at),
                       static_cast<std::uint8_t>(value(rng)));
          break;
      }
    }
    DecodeCounters totals;
    const std::vector<Frame> frames = decodeInChunks(bytes, rng, totals);
    // Most frames survive a sparse mutation; each corrupted one costs at most itself.
    EXPECT_GE(frames.size() + static_cast<std::size_t>(mutations), 1100u) << "round " << round;
    for (const Frame& f : frames) {
      const Bytes image = wireImage(f);
      ASSERT_NE(std::search(bytes.begin(), bytes.end(), image.begin(), image.end()), bytes.end())
          << "round " << round << ": delivered a frame not present with a valid CRC";
    }
  }
}

TEST(MavlinkDecoderFuzz, NoiseNeverCrashesAndIsAllGarbage) {
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> value(0, 255);
  Bytes noise(200000);
  for (auto& b : noise) {
    b = static_cast<std::uint8_t>(value(rng));
  }
  // Many STX bytes make many candidate frames; all must fail cleanly.
  for (std::size_t i = 0; i < noise.size(); i += 97) {
    noise[i] = kStxV2;
  }
  DecodeCounters totals;
  const std::vector<Frame> frames = decodeInChunks(noise, rng, totals);
  for (const Frame& f : frames) {  // a 16-bit CRC can match by chance; the frame then is genuine
    const Bytes image = wireImage(f);
    EXPECT_NE(std::search(noise.begin(), noise.end(), image.begin(), image.end()), noise.end());
  }
  EXPECT_LE(frames.size(), 2u);
  EXPECT_GT(totals.unknown_id + totals.bad_crc + totals.bad_length + totals.unsupported_flags,
            1000u);
}

TEST(MavlinkDecoderFuzz, TruncatedFramesAtEveryLengthAreSafe) {
  const Bytes clean = telemetryStream(1);
  for (std::size_t n = 0; n <= clean.size(); ++n) {
    FrameDecoder decoder;
    const DecodeResult r = decoder.feed(std::span(clean).first(n));
    EXPECT_LE(r.frames.size(), 11u);
    EXPECT_EQ(r.counters.bad_crc, 0u);
  }
}

}  // namespace
}  // namespace irgs::comms::mavlink
